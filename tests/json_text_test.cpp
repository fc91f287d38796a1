#include "scanloc/io/json_text.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <random>
#include <string>

namespace scanloc {
namespace {

std::string Text(const nlohmann::json& value) {
  std::string text;
  AppendJsonText(value, text);
  return text;
}

// Doubles of every magnitude dump() writes in fixed or exponent form, integers of both signs
// and widths, and the strings it must escape: the text must be dump()'s, byte for byte.
TEST(JsonText, WritesWhatDumpWritesByteForByte) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> exponent(-30.0, 30.0), mantissa(-1.0, 1.0);
  nlohmann::json numbers = nlohmann::json::array();
  for (int i = 0; i < 5000; ++i) numbers.push_back(mantissa(rng) * std::pow(10.0, exponent(rng)));
  for (const double special : {0.0,
                               -0.0,
                               1.0,
                               -1.0,
                               0.1,
                               1e-5,
                               1e-4,
                               1e15,
                               1e16,
                               1e17,
                               123456789012345678.0,
                               std::numeric_limits<double>::min(),
                               std::numeric_limits<double>::denorm_min(),
                               std::numeric_limits<double>::max(),
                               std::numeric_limits<double>::lowest(),
                               std::numeric_limits<double>::quiet_NaN(),
                               std::numeric_limits<double>::infinity(),
                               -std::numeric_limits<double>::infinity(),
                               1.585457080080388e-20,
                               0.00028000000000000003})
    numbers.push_back(special);
  for (const std::int64_t integer :
       {std::int64_t{0}, std::int64_t{-1}, std::int64_t{7}, std::int64_t{-1234567},
        std::numeric_limits<std::int64_t>::min(), std::numeric_limits<std::int64_t>::max()})
    numbers.push_back(integer);
  numbers.push_back(std::numeric_limits<std::uint64_t>::max());
  numbers.push_back(std::uint64_t{42});
  EXPECT_EQ(Text(numbers), numbers.dump());

  const nlohmann::json record = {
      {"plain", "rule 2: expected value too high"},
      {"quotes \"and\" \\backslashes\\", "tab\there\nnew line \x01 control"},
      {"utf-8 ° é ✓", "/logs/café/aces.clf.gz:7"},
      {"empty", ""},
      {"nested", {{"z", nullptr}, {"a", {true, false, nlohmann::json::array()}}}},
      {"object", nlohmann::json::object()},
      {"numbers", numbers}};
  EXPECT_EQ(Text(record), record.dump());
}

TEST(JsonText, RefusesInvalidUtf8AsDumpDoes) {
  const nlohmann::json bad = {{"origin", std::string("log\xff.clf")}};
  EXPECT_THROW(bad.dump(), nlohmann::json::type_error);
  std::string text;
  EXPECT_THROW(AppendJsonText(bad, text), nlohmann::json::type_error);
}

TEST(JsonText, Appends) {
  std::string text = "before ";
  AppendJsonText({1, 2}, text);
  EXPECT_EQ(text, "before [1,2]");
}

}  // namespace
}  // namespace scanloc
