#include "scanloc/io/input_format.hpp"

#include <zlib.h>

#include <array>
#include <cctype>
#include <cerrno>
#include <cstring>
#include <fstream>
#include <sstream>
#include <stdexcept>

namespace scanloc {
namespace {

constexpr char kRosBagMagic[] = "#ROSBAG V2.0";
// Enough to get past a log's comment header to its first message.
constexpr std::size_t kSniffBytes = 64 * 1024;

// Message types of CARMEN's logger (old and new style) that may open a log.
constexpr std::array<const char*, 16> kCarmenKeywords = {
    "FLASER",      "RLASER",      "LASER3",    "LASER4",    "ODOM",      "PARAM",
    "ROBOTLASER1", "ROBOTLASER2", "RAWLASER1", "RAWLASER2", "RAWLASER3", "RAWLASER4",
    "TRUEPOS",     "SYNC",        "NMEAGGA",   "NMEARMC"};

std::string RawPrefix(const std::string& path, std::size_t bytes) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open " + path + ": " + std::strerror(errno));
  std::string text(bytes, '\0');
  in.read(text.data(), static_cast<std::streamsize>(bytes));
  text.resize(static_cast<std::size_t>(in.gcount()));
  return text;
}

// The first bytes after gzip decompression (zlib reads plain files as they are).
std::string DecompressedPrefix(const std::string& path) {
  gzFile file = gzopen(path.c_str(), "rb");
  if (file == nullptr) throw std::runtime_error("cannot open " + path);
  std::string text(kSniffBytes, '\0');
  const int read = gzread(file, text.data(), static_cast<unsigned>(text.size()));
  gzclose(file);
  text.resize(read > 0 ? static_cast<std::size_t>(read) : 0);
  return text;
}

// True when a line of the text starts with a CARMEN message keyword.
bool HoldsCarmenMessage(const std::string& text) {
  std::istringstream lines(text);
  std::string line;
  while (std::getline(lines, line)) {
    std::istringstream fields(line);
    std::string first;
    if (!(fields >> first)) continue;
    for (const char* keyword : kCarmenKeywords)
      if (first == keyword) return true;
  }
  return false;
}

}  // namespace

std::string AcceptedInputFormats() {
  return "a CARMEN log (FLASER, ROBOTLASER1, ODOM, PARAM lines; plain or gzip), a ROS 1 bag "
         "(starting with \"#ROSBAG V2.0\"), or a scanloc sequence (JSON Lines starting with "
         "{\"scanloc_sequence\": 1})";
}

InputFormat DetectInputFormat(const std::string& path) {
  const std::string raw = RawPrefix(path, sizeof kRosBagMagic - 1);
  if (raw == kRosBagMagic) return InputFormat::kRosBag;
  const std::string text = DecompressedPrefix(path);
  const auto first = text.find_first_not_of(" \t\r\n");
  const bool gzip = raw.size() >= 2 && static_cast<unsigned char>(raw[0]) == 0x1f &&
                    static_cast<unsigned char>(raw[1]) == 0x8b;
  if (first != std::string::npos && text[first] == '{' && !gzip) return InputFormat::kScanSequence;
  if (HoldsCarmenMessage(text)) return InputFormat::kCarmenLog;
  throw std::runtime_error(path + ": " + (text.empty() ? "empty file" : "unrecognised content") +
                           "; expected " + AcceptedInputFormats());
}

}  // namespace scanloc
