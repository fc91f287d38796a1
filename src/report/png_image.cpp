#include "scanloc/report/png_image.hpp"

#include <zlib.h>

#include <stdexcept>

namespace scanloc {
namespace {

void AppendBigEndian(std::string& out, std::uint32_t value) {
  for (int shift = 24; shift >= 0; shift -= 8) out.push_back(static_cast<char>(value >> shift));
}

// A chunk: length, type, data, CRC-32 of type and data (PNG spec §5.3).
void AppendChunk(std::string& png, const char type[4], const std::string& data) {
  AppendBigEndian(png, static_cast<std::uint32_t>(data.size()));
  const std::string body = std::string(type, 4) + data;
  png += body;
  const auto* bytes = reinterpret_cast<const Bytef*>(body.data());
  AppendBigEndian(png, static_cast<std::uint32_t>(
                           crc32(crc32(0L, Z_NULL, 0), bytes, static_cast<uInt>(body.size()))));
}

// Each row prefixed with filter type 0 (none), then deflated.
std::string CompressedRows(std::size_t width, std::size_t height,
                           const std::vector<std::uint8_t>& pixels) {
  std::string raw;
  raw.reserve((width + 1) * height);
  for (std::size_t y = 0; y < height; ++y) {
    raw.push_back('\0');
    raw.append(reinterpret_cast<const char*>(pixels.data() + y * width), width);
  }
  uLongf size = compressBound(static_cast<uLong>(raw.size()));
  std::string compressed(size, '\0');
  if (compress2(reinterpret_cast<Bytef*>(compressed.data()), &size,
                reinterpret_cast<const Bytef*>(raw.data()), static_cast<uLong>(raw.size()),
                Z_BEST_COMPRESSION) != Z_OK)
    throw std::runtime_error("GreyscalePng: zlib could not compress the image");
  compressed.resize(size);
  return compressed;
}

}  // namespace

std::string GreyscalePng(std::size_t width, std::size_t height,
                         const std::vector<std::uint8_t>& pixels) {
  if (width == 0 || height == 0 || pixels.size() != width * height)
    throw std::invalid_argument("GreyscalePng: expected width × height > 0 pixels");
  std::string png = "\x89PNG\r\n\x1a\n";
  std::string header;
  AppendBigEndian(header, static_cast<std::uint32_t>(width));
  AppendBigEndian(header, static_cast<std::uint32_t>(height));
  header += std::string("\x08\x00\x00\x00\x00", 5);  // 8 bits, grey, deflate, filters, no interlace
  AppendChunk(png, "IHDR", header);
  AppendChunk(png, "IDAT", CompressedRows(width, height, pixels));
  AppendChunk(png, "IEND", "");
  return png;
}

std::string Base64(const std::string& bytes) {
  static constexpr char kDigits[] =
      "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  for (std::size_t i = 0; i < bytes.size(); i += 3) {
    std::uint32_t group = static_cast<std::uint8_t>(bytes[i]) << 16;
    if (i + 1 < bytes.size()) group |= static_cast<std::uint8_t>(bytes[i + 1]) << 8;
    if (i + 2 < bytes.size()) group |= static_cast<std::uint8_t>(bytes[i + 2]);
    out.push_back(kDigits[(group >> 18) & 63]);
    out.push_back(kDigits[(group >> 12) & 63]);
    out.push_back(i + 1 < bytes.size() ? kDigits[(group >> 6) & 63] : '=');
    out.push_back(i + 2 < bytes.size() ? kDigits[group & 63] : '=');
  }
  return out;
}

std::string GreyscalePngDataUri(std::size_t width, std::size_t height,
                                const std::vector<std::uint8_t>& pixels) {
  return "data:image/png;base64," + Base64(GreyscalePng(width, height, pixels));
}

}  // namespace scanloc
