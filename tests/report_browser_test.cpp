// The report in a real browser: headless Chromium (Debian's `chromium`, installed by
// scripts/install-deps.sh) loads the page of a synthetic session without a console message,
// parses every figure, and its screenshot shows them. Skips with a message when Chromium is absent.
// SCANLOC_REPORT_SCREENSHOT=DIR keeps the page and the screenshot.

#include <gtest/gtest.h>
#include <zlib.h>  // scanloc links zlib (CARMEN's gzip logs); the PNG is decoded with it here

#include <array>
#include <cstdint>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <stdexcept>

#include "report_fixtures.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

using testing::CommandResult;
using testing::ReadText;

// The Chromium executable in PATH, or "".
std::string FindChromium() {
  const char* path = std::getenv("PATH");
  if (!path) return "";
  std::stringstream folders(path);
  for (std::string folder; std::getline(folders, folder, ':');)
    for (const char* name : {"chromium", "chromium-browser"}) {
      const std::filesystem::path candidate = std::filesystem::path(folder) / name;
      if (::access(candidate.c_str(), X_OK) == 0) return candidate.string();
    }
  return "";
}

std::size_t Count(const std::string& text, const std::string& part) {
  std::size_t count = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1))
    ++count;
  return count;
}

struct Image {
  std::uint32_t width = 0, height = 0;
  std::vector<std::array<std::uint8_t, 3>> pixels;  // RGB, row by row
};

std::uint32_t BigEndian(const std::string& bytes, std::size_t at) {
  return (std::uint32_t(std::uint8_t(bytes[at])) << 24) |
         (std::uint32_t(std::uint8_t(bytes[at + 1])) << 16) |
         (std::uint32_t(std::uint8_t(bytes[at + 2])) << 8) |
         std::uint32_t(std::uint8_t(bytes[at + 3]));
}

// Decodes an 8-bit, non-interlaced RGB or RGBA PNG (what Chromium writes); throws
// std::runtime_error saying what is wrong otherwise.
Image DecodePng(const std::string& png) {
  static const std::string kSignature = "\x89PNG\r\n\x1a\n";
  if (png.compare(0, kSignature.size(), kSignature) != 0)
    throw std::runtime_error("not a PNG (no signature)");
  Image image;
  int channels = 0;
  std::string compressed;
  for (std::size_t at = kSignature.size(); at + 8 <= png.size();) {
    const std::uint32_t length = BigEndian(png, at);
    const std::string type = png.substr(at + 4, 4);
    if (at + 12 + length > png.size()) throw std::runtime_error("PNG chunk " + type + " cut short");
    const std::string data = png.substr(at + 8, length);
    if (type == "IHDR") {
      image.width = BigEndian(data, 0);
      image.height = BigEndian(data, 4);
      const int depth = std::uint8_t(data[8]), colour = std::uint8_t(data[9]);
      const int interlace = std::uint8_t(data[12]);
      if (depth != 8 || (colour != 2 && colour != 6) || interlace != 0)
        throw std::runtime_error("unexpected PNG format: depth " + std::to_string(depth) +
                                 ", colour type " + std::to_string(colour));
      channels = colour == 2 ? 3 : 4;
    } else if (type == "IDAT") {
      compressed += data;
    } else if (type == "IEND") {
      break;
    }
    at += 12 + length;
  }
  if (channels == 0) throw std::runtime_error("PNG without IHDR");
  const std::size_t stride = std::size_t(image.width) * channels;
  std::string raw((stride + 1) * image.height, '\0');
  uLongf raw_size = raw.size();
  if (uncompress(reinterpret_cast<Bytef*>(raw.data()), &raw_size,
                 reinterpret_cast<const Bytef*>(compressed.data()), compressed.size()) != Z_OK ||
      raw_size != raw.size())
    throw std::runtime_error("PNG image data does not inflate to width × height");
  // Undo the row filters (PNG spec §9): None, Sub, Up, Average, Paeth.
  std::vector<std::uint8_t> previous(stride, 0), row(stride);
  image.pixels.reserve(std::size_t(image.width) * image.height);
  for (std::uint32_t y = 0; y < image.height; ++y) {
    const std::uint8_t filter = raw[y * (stride + 1)];
    for (std::size_t i = 0; i < stride; ++i) {
      const int x = std::uint8_t(raw[y * (stride + 1) + 1 + i]);
      const int a = i >= std::size_t(channels) ? row[i - channels] : 0;
      const int b = previous[i];
      const int c = i >= std::size_t(channels) ? previous[i - channels] : 0;
      int predictor = 0;
      switch (filter) {
        case 0:
          break;
        case 1:
          predictor = a;
          break;
        case 2:
          predictor = b;
          break;
        case 3:
          predictor = (a + b) / 2;
          break;
        case 4: {
          const int p = a + b - c, pa = std::abs(p - a), pb = std::abs(p - b), pc = std::abs(p - c);
          predictor = pa <= pb && pa <= pc ? a : pb <= pc ? b : c;
          break;
        }
        default:
          throw std::runtime_error("PNG row " + std::to_string(y) + " has filter " +
                                   std::to_string(filter));
      }
      row[i] = std::uint8_t(x + predictor);
    }
    for (std::uint32_t px = 0; px < image.width; ++px)
      image.pixels.push_back({row[px * channels], row[px * channels + 1], row[px * channels + 2]});
    previous.swap(row);
  }
  return image;
}

// Pixels within `tolerance` of the colour in every channel.
std::size_t CountNear(const Image& image, std::array<int, 3> colour, int tolerance) {
  std::size_t count = 0;
  for (const auto& p : image.pixels)
    count += std::abs(p[0] - colour[0]) <= tolerance && std::abs(p[1] - colour[1]) <= tolerance &&
             std::abs(p[2] - colour[2]) <= tolerance;
  return count;
}

class ReportInBrowser : public testing::TemporaryDirTest {
 protected:
  void SetUp() override {
    TemporaryDirTest::SetUp();
    chromium_ = FindChromium();
  }
  // Chromium headless on `url` with extra flags; never more than two minutes.
  CommandResult Chromium(const std::vector<std::string>& flags, const std::string& url) const {
    std::vector<std::string> words = {"timeout",
                                      "120",
                                      chromium_,
                                      "--headless",
                                      "--no-sandbox",
                                      "--disable-gpu",
                                      "--user-data-dir=" + dir_ + "/profile"};
    words.insert(words.end(), flags.begin(), flags.end());
    words.push_back(url);
    return testing::RunCommand(words, dir_);
  }
  std::string chromium_;
};

TEST_F(ReportInBrowser, PageLoadsWithoutConsoleMessagesAndItsScreenshotShowsTheFigures) {
  if (chromium_.empty())
    GTEST_SKIP() << "chromium is not installed (apt-get install chromium, or run "
                    "scripts/install-deps.sh): the report's browser test cannot run";
  const std::string run = testing::MakeClassroomRun(dir_);
  ASSERT_FALSE(run.empty());
  const CommandResult report = testing::RunScanloc({"report", run}, dir_);
  ASSERT_TRUE(report.exited && report.exit_code == 0) << report;
  const std::string page = run + "/report.html";
  const std::string html = ReadText(page);
  const std::string url = "file://" + page;

  // The DOM Chromium built holds every figure of the file: no markup broke the parse.
  const CommandResult dom = Chromium({"--dump-dom"}, url);
  ASSERT_TRUE(dom.exited && dom.exit_code == 0) << dom;
  const std::size_t figures = Count(html, "<svg ");
  EXPECT_GE(figures, 2u + 3u * 3u);  // trajectory, moments, 3+ iterations with 3 figures each
  EXPECT_EQ(Count(dom.out, "<svg "), figures);
  EXPECT_EQ(Count(dom.out, "<section class=\"iteration"),
            Count(html, "<section class=\"iteration"));
  EXPECT_EQ(Count(dom.out, "<table"), Count(html, "<table"));

  // A screenshot tall enough for the summary, the trajectory (over the grid and over the points),
  // the moments and the first iteration; the console stays silent (no error, no failed load: the
  // page is self-contained).
  const int width = 1280, height = 4000;
  const std::string screenshot = dir_ + "/report.png";
  const CommandResult shot =
      Chromium({"--hide-scrollbars", "--screenshot=" + screenshot,
                "--window-size=" + std::to_string(width) + "," + std::to_string(height),
                "--enable-logging=stderr", "--v=0"},
               url);
  ASSERT_TRUE(shot.exited && shot.exit_code == 0) << shot;
  std::stringstream log(shot.err);
  for (std::string line; std::getline(log, line);)
    EXPECT_EQ(line.find(":CONSOLE"), std::string::npos) << "console message: " << line;
  ASSERT_TRUE(std::filesystem::exists(screenshot)) << shot;
  // The proof to keep (e.g. a CI artifact): SCANLOC_REPORT_SCREENSHOT=DIR copies the page and
  // its screenshot there.
  if (const char* keep = std::getenv("SCANLOC_REPORT_SCREENSHOT")) {
    std::filesystem::create_directories(keep);
    for (const std::string& file : {screenshot, page})
      std::filesystem::copy_file(
          file, std::filesystem::path(keep) / std::filesystem::path(file).filename(),
          std::filesystem::copy_options::overwrite_existing);
  }
  Image image;
  ASSERT_NO_THROW(image = DecodePng(ReadText(screenshot)));
  EXPECT_EQ(image.width, std::uint32_t(width));
  EXPECT_EQ(image.height, std::uint32_t(height));
  std::size_t ink = 0;
  for (const auto& p : image.pixels) ink += p[0] < 235 || p[1] < 235 || p[2] < 235;
  const double ink_share = double(ink) / image.pixels.size();
  EXPECT_GT(ink_share, 0.02) << "the page looks blank";
  EXPECT_LT(ink_share, 0.6) << "the page looks filled with one colour";
  // Colours only the figures use: the scan's orange, the trajectory's blue, the map's grey dots.
  EXPECT_GT(CountNear(image, {0xe6, 0x61, 0x01}, 40), 100u) << "no scan drawn";
  EXPECT_GT(CountNear(image, {0x21, 0x66, 0xac}, 40), 100u) << "no trajectory drawn";
  EXPECT_GT(CountNear(image, {0x1a, 0x98, 0x50}, 40), 50u) << "no validated iteration drawn";
}

}  // namespace
}  // namespace scanloc
