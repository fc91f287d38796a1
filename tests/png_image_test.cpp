// GreyscalePng and Base64: the report's embedded raster of the occupancy grid.
#include "scanloc/report/png_image.hpp"

#include <gtest/gtest.h>
#include <zlib.h>

#include <stdexcept>

namespace scanloc {
namespace {

std::uint32_t BigEndian(const std::string& bytes, std::size_t at) {
  std::uint32_t value = 0;
  for (std::size_t i = 0; i < 4; ++i) value = (value << 8) | std::uint8_t(bytes[at + i]);
  return value;
}

TEST(Base64, EncodesTheRfc4648TestVectors) {
  EXPECT_EQ(Base64(""), "");
  EXPECT_EQ(Base64("f"), "Zg==");
  EXPECT_EQ(Base64("fo"), "Zm8=");
  EXPECT_EQ(Base64("foo"), "Zm9v");
  EXPECT_EQ(Base64("foob"), "Zm9vYg==");
  EXPECT_EQ(Base64("fooba"), "Zm9vYmE=");
  EXPECT_EQ(Base64("foobar"), "Zm9vYmFy");
  EXPECT_EQ(Base64(std::string("\xff\x00\x80", 3)), "/wCA");
}

TEST(GreyscalePng, ChunksCarryValidCrcsAndThePixelsInflateBackRowByRow) {
  const std::size_t width = 5, height = 3;
  std::vector<std::uint8_t> pixels(width * height);
  for (std::size_t i = 0; i < pixels.size(); ++i) pixels[i] = static_cast<std::uint8_t>(17 * i);
  const std::string png = GreyscalePng(width, height, pixels);
  ASSERT_EQ(png.compare(0, 8, "\x89PNG\r\n\x1a\n"), 0);
  std::string idat;
  std::vector<std::string> types;
  for (std::size_t at = 8; at < png.size();) {
    const std::uint32_t length = BigEndian(png, at);
    const std::string type = png.substr(at + 4, 4), data = png.substr(at + 8, length);
    const std::string body = png.substr(at + 4, 4 + length);
    EXPECT_EQ(BigEndian(png, at + 8 + length),
              crc32(0, reinterpret_cast<const Bytef*>(body.data()), body.size()))
        << type;
    if (type == "IHDR") {
      EXPECT_EQ(BigEndian(data, 0), width);
      EXPECT_EQ(BigEndian(data, 4), height);
      EXPECT_EQ(data.substr(8), std::string("\x08\x00\x00\x00\x00", 5));  // 8-bit grey
    }
    if (type == "IDAT") idat += data;
    types.push_back(type);
    at += 12 + length;
  }
  EXPECT_EQ(types, (std::vector<std::string>{"IHDR", "IDAT", "IEND"}));
  std::string raw((width + 1) * height, '\x7f');
  uLongf size = raw.size();
  ASSERT_EQ(uncompress(reinterpret_cast<Bytef*>(raw.data()), &size,
                       reinterpret_cast<const Bytef*>(idat.data()), idat.size()),
            Z_OK);
  ASSERT_EQ(size, raw.size());
  for (std::size_t y = 0; y < height; ++y) {
    EXPECT_EQ(raw[y * (width + 1)], '\0');  // filter: none
    for (std::size_t x = 0; x < width; ++x)
      EXPECT_EQ(std::uint8_t(raw[y * (width + 1) + 1 + x]), pixels[y * width + x]);
  }
}

TEST(GreyscalePng, ADataUriIsTheBase64OfThePngAndAWrongPixelCountIsRefused) {
  const std::vector<std::uint8_t> pixels = {0, 255};
  EXPECT_EQ(GreyscalePngDataUri(2, 1, pixels),
            "data:image/png;base64," + Base64(GreyscalePng(2, 1, pixels)));
  EXPECT_THROW(GreyscalePng(3, 1, pixels), std::invalid_argument);
  EXPECT_THROW(GreyscalePng(0, 0, {}), std::invalid_argument);
}

}  // namespace
}  // namespace scanloc
