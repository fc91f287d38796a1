#include "pcd_header.hpp"

#include <array>
#include <cctype>
#include <cstdint>
#include <filesystem>
#include <fstream>
#include <istream>
#include <limits>
#include <set>
#include <stdexcept>
#include <string>
#include <vector>

#include "scanloc/common/bounded_line.hpp"
#include "scanloc/common/parse_error.hpp"

namespace scanloc {
namespace {

// Bounds of a sane PCD header: field names per point, values per field, and the bytes a header
// line may take (a FIELDS line of kMaxPcdFields names fits many times over).
constexpr std::size_t kMaxPcdFields = 256;
constexpr long kMaxPcdFieldCount = 4096;
constexpr std::size_t kMaxPcdHeaderLineBytes = 64 * 1024;
// LZF's best case stores a back reference of 264 bytes in 3: no binary_compressed body expands
// more than 88 times. 128 rounds that up.
constexpr double kMaxLzfExpansion = 128.0;

// What the header announces, with the line of each statement for the errors.
struct PcdHeader {
  std::size_t fields = 0, fields_line = 0;
  std::vector<long> sizes, counts;
  std::size_t sizes_line = 0, counts_line = 0;
  double width = -1.0, height = -1.0, points = -1.0;
  std::size_t points_line = 0, data_line = 0;
  std::string data;
  std::uint64_t data_offset = 0;  // bytes before the body
};

// The value of a WIDTH, HEIGHT or POINTS statement: an integer in [0, 2^32).
double PcdDimension(const std::vector<std::string>& fields, const std::string& path,
                    std::size_t line) {
  if (fields.size() != 2) throw ParseError(path, line, "expected '" + fields[0] + " <count>'");
  const long value = ParseInteger(fields[1], path, line, fields[0] + " as a count");
  if (value < 0 || value > static_cast<long>(std::numeric_limits<std::uint32_t>::max()))
    throw ParseError(path, line, "expected " + fields[0] + " in [0, 2^32), got " + fields[1]);
  return static_cast<double>(value);
}

// SIZE or COUNT: one integer in [1, maximum] per field.
std::vector<long> PcdPerField(const std::vector<std::string>& fields, const std::string& path,
                              std::size_t line, long maximum) {
  if (fields.size() > kMaxPcdFields + 1)
    throw ParseError(path, line, "more than " + std::to_string(kMaxPcdFields) + " fields");
  std::vector<long> values;
  for (std::size_t i = 1; i < fields.size(); ++i) {
    values.push_back(ParseInteger(fields[i], path, line, fields[0] + " value"));
    if (values.back() < 1 || values.back() > maximum)
      throw ParseError(path, line,
                       "expected " + fields[0] + " values in [1, " + std::to_string(maximum) +
                           "], got " + fields[i]);
  }
  return values;
}

// The statements of a PCD header. PCL takes a line for one of them when its first word begins
// with that statement's name.
constexpr std::array<const char*, 11> kPcdStatements = {"VERSION",   "FIELDS", "COLUMNS", "SIZE",
                                                        "TYPE",      "COUNT",  "WIDTH",   "HEIGHT",
                                                        "VIEWPOINT", "POINTS", "DATA"};

// The statement PCL reads in a line whose first word is `word`, or "" for none.
std::string PclStatement(const std::string& word) {
  for (const char* statement : kPcdStatements)
    if (word.rfind(statement, 0) == 0) return statement;
  return "";
}

// The words of one header line, or none for a comment. Refuses what PCL and scanloc would read
// apart: control characters, a '#' inside a statement, a line of white space (PCL's header ends
// there), a word PCL takes for a statement by its prefix, a name that is no statement at all.
std::vector<std::string> HeaderWords(const std::string& text, const std::string& path,
                                     std::size_t line) {
  for (const char c : text)
    if (std::iscntrl(static_cast<unsigned char>(c)) && c != '\t' && c != '\r')
      throw ParseError(path, line, "expected printable text in the PCD header");
  const std::size_t first = text.find_first_not_of(" \t\r");
  if (first != std::string::npos && text[first] == '#') return {};
  if (text.find('#') != std::string::npos)
    throw ParseError(path, line, "expected '#' only at the start of a comment line");
  std::vector<std::string> words = SplitFields(text, kMaxPcdFields + 1);
  if (words.empty())
    throw ParseError(path, line, "expected a header statement, got a line of white space");
  const std::string statement = PclStatement(words[0]);
  if (statement != words[0])
    throw ParseError(path, line,
                     "expected a PCD header statement (VERSION, FIELDS, SIZE, TYPE, COUNT, WIDTH, "
                     "HEIGHT, VIEWPOINT, POINTS, DATA), got '" +
                         words[0] + "'");
  return words;
}

// Reads the statements of one header line into `header`; true at DATA.
bool ReadStatement(const std::vector<std::string>& fields, const std::string& path,
                   std::size_t line, PcdHeader& header) {
  const std::string& key = fields[0];
  if (key == "FIELDS" || key == "COLUMNS") {
    if (fields.size() > kMaxPcdFields + 1)
      throw ParseError(path, line, "more than " + std::to_string(kMaxPcdFields) + " fields");
    header.fields = fields.size() - 1;
    header.fields_line = line;
  } else if (key == "SIZE") {
    header.sizes = PcdPerField(fields, path, line, 8);
    for (const long size : header.sizes)
      if (size != 1 && size != 2 && size != 4 && size != 8)
        throw ParseError(path, line, "expected SIZE values of 1, 2, 4 or 8 bytes");
    header.sizes_line = line;
  } else if (key == "COUNT") {
    header.counts = PcdPerField(fields, path, line, kMaxPcdFieldCount);
    header.counts_line = line;
  } else if (key == "WIDTH") {
    header.width = PcdDimension(fields, path, line);
  } else if (key == "HEIGHT") {
    header.height = PcdDimension(fields, path, line);
  } else if (key == "POINTS") {
    header.points = PcdDimension(fields, path, line);
    header.points_line = line;
  } else if (key == "DATA") {
    if (fields.size() != 2 ||
        (fields[1] != "ascii" && fields[1] != "binary" && fields[1] != "binary_compressed"))
      throw ParseError(path, line, "expected 'DATA ascii|binary|binary_compressed'");
    header.data = fields[1];
    header.data_line = line;
    return true;
  }
  return false;
}

// PCL reads on after DATA for as long as lines look like statements or comments: refuses a body
// whose first lines PCL would take for more header. `line` is the body's first line.
void CheckBodyIsNoHeader(std::istream& in, const std::string& path, std::size_t line) {
  constexpr std::size_t kLongestStatement = 9;  // VIEWPOINT
  for (;; ++line) {
    int c = in.get();
    if (c == '\n') continue;  // PCL skips empty lines
    while (c == ' ' || c == '\t' || c == '\r' || c == '\v' || c == '\f') c = in.get();
    std::string word;
    while (c != std::char_traits<char>::eof() && !std::isspace(c) &&
           word.size() < kLongestStatement) {
      word.push_back(static_cast<char>(c));
      c = in.get();
    }
    if (word.empty()) return;  // the end of the file, or a blank line: PCL's header ends
    if (word[0] != '#') {
      if (PclStatement(word).empty()) return;
      throw ParseError(path, line,
                       "expected the points after DATA, got a line PCL reads as its " +
                           PclStatement(word) + " statement");
    }
    if (c != '\n') in.ignore(std::numeric_limits<std::streamsize>::max(), '\n');
  }
}

// Reads the header statements up to DATA, each line bounded and each statement at most once, and
// checks the line after DATA.
PcdHeader ReadPcdHeader(std::istream& in, const std::string& path) {
  PcdHeader header;
  std::set<std::string> seen;
  std::string text;
  for (std::size_t line = 1; ReadBoundedLine(in, text, path, line, kMaxPcdHeaderLineBytes);
       ++line) {
    header.data_offset += text.size() + 1;
    if (text.empty()) continue;  // PCL skips empty lines
    const std::vector<std::string> words = HeaderWords(text, path, line);
    if (words.empty()) continue;
    const std::string name = words[0] == "COLUMNS" ? "FIELDS" : words[0];
    if (!seen.insert(name).second)
      throw ParseError(path, line, "expected one " + name + " statement, got a second");
    if (ReadStatement(words, path, line, header)) {
      CheckBodyIsNoHeader(in, path, line + 1);
      return header;
    }
  }
  throw ParseError(path, 1, "no DATA line, not a PCD file");
}

// Checks the header's statements against each other and against the file's size, so that no
// count it announces is believed beyond what the file can hold.
}  // namespace

void CheckPcdHeader(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error("cannot open point map " + path);
  const PcdHeader h = ReadPcdHeader(in, path);
  if (h.fields == 0) throw ParseError(path, h.data_line, "no FIELDS in the PCD header");
  if (h.sizes.size() != h.fields)
    throw ParseError(path, h.sizes_line != 0 ? h.sizes_line : h.data_line,
                     "expected one SIZE per field (" + std::to_string(h.fields) + ")");
  if (!h.counts.empty() && h.counts.size() != h.fields)
    throw ParseError(path, h.counts_line,
                     "expected one COUNT per field (" + std::to_string(h.fields) + ")");
  double point_bytes = 0.0, values_per_point = 0.0;
  for (std::size_t i = 0; i < h.fields; ++i) {
    const double count = h.counts.empty() ? 1.0 : static_cast<double>(h.counts[i]);
    point_bytes += count * static_cast<double>(h.sizes[i]);
    values_per_point += count;
  }
  const double points = h.width >= 0.0 && h.height >= 0.0 ? h.width * h.height : h.points;
  if (points < 0.0) throw ParseError(path, h.data_line, "no WIDTH and HEIGHT or POINTS");
  if (h.points >= 0.0 && h.points != points)
    throw ParseError(path, h.points_line, "POINTS differs from WIDTH × HEIGHT");
  std::error_code error;
  const double body_bytes =
      static_cast<double>(std::filesystem::file_size(path, error)) - h.data_offset;
  double needed_bytes = points * point_bytes;                                   // binary
  if (h.data == "ascii") needed_bytes = points * values_per_point * 2.0 - 1.0;  // "v v\n"
  if (h.data == "binary_compressed")
    needed_bytes = points == 0.0 ? 0.0 : 8.0 + points * point_bytes / kMaxLzfExpansion;
  if (error || needed_bytes > body_bytes)
    throw ParseError(path, h.points_line != 0 ? h.points_line : h.data_line,
                     std::to_string(static_cast<std::uint64_t>(points)) + " points of " +
                         std::to_string(static_cast<std::uint64_t>(point_bytes)) +
                         " bytes announced (DATA " + h.data + "), but the file holds " +
                         std::to_string(static_cast<std::int64_t>(body_bytes)) +
                         " bytes after its header");
}

}  // namespace scanloc
