#include "scanloc/io/json_writer.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <limits>
#include <nlohmann/json.hpp>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

namespace scanloc {
namespace {

// Writes an nlohmann value through the writer, its members in reverse key order where `reverse`
// (dump()'s order is the writer's job).
void Write(const nlohmann::json& value, JsonWriter& writer, bool reverse) {
  if (value.is_object()) {
    writer.BeginObject();
    std::vector<std::string> keys;
    for (const auto& [key, member] : value.items()) keys.push_back(key);
    if (reverse) std::reverse(keys.begin(), keys.end());
    for (const std::string& key : keys) {
      writer.Key(key);
      Write(value.at(key), writer, reverse);
    }
    writer.EndObject();
  } else if (value.is_array()) {
    writer.BeginArray();
    for (const nlohmann::json& element : value) Write(element, writer, reverse);
    writer.EndArray();
  } else if (value.is_string()) {
    writer.Value(value.get_ref<const std::string&>());
  } else if (value.is_boolean()) {
    writer.Value(value.get<bool>());
  } else if (value.is_number_unsigned()) {
    writer.Value(value.get<std::uint64_t>());
  } else if (value.is_number_integer()) {
    writer.Value(value.get<std::int64_t>());
  } else if (value.is_number_float()) {
    writer.Value(value.get<double>());
  } else {
    writer.Null();
  }
}

std::string Text(const nlohmann::json& value, bool reverse = false) {
  std::string text;
  JsonWriter writer(text);
  Write(value, writer, reverse);
  EXPECT_TRUE(writer.complete());
  return text;
}

nlohmann::json Numbers() {
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
  return numbers;
}

nlohmann::json Record() {
  return {{"plain", "rule 2: expected value too high"},
          {"quotes \"and\" \\backslashes\\", "tab\there\nnew line \x01 control"},
          {"utf-8 ° é ✓", "/logs/café/aces.clf.gz:7"},
          {"empty", ""},
          {"T_world_robot", {{"yaw_rad", 0.5}, {"x_m", 1.0}, {"y_m", -2.0}}},
          {"nested", {{"z", nullptr}, {"a", {true, false, nlohmann::json::array()}}}},
          {"object", nlohmann::json::object()},
          {"numbers", Numbers()}};
}

// Doubles of every magnitude dump() writes in fixed or exponent form, integers of both signs
// and widths, and the strings it must escape: the text must be dump()'s, byte for byte.
TEST(JsonWriter, WritesWhatDumpWritesByteForByte) {
  const nlohmann::json numbers = Numbers();
  EXPECT_EQ(Text(numbers), numbers.dump());
  EXPECT_EQ(Text(Record()), Record().dump());
}

// Members given in any order come out in dump()'s (by key), at every depth.
TEST(JsonWriter, WritesEachObjectsMembersInDumpsOrderWhateverTheirOrderGiven) {
  EXPECT_EQ(Text(Record(), true), Record().dump());
  std::string text;
  JsonWriter writer(text);
  writer.BeginObject();
  writer.Member("total", 3);
  writer.Key("b");
  writer.BeginObject();
  writer.Member("z", std::vector<int>{1, 2});
  writer.Member("a", "x");
  writer.EndObject();
  writer.Member("a", true);
  writer.EndObject();
  EXPECT_EQ(text, R"({"a":true,"b":{"a":"x","z":[1,2]},"total":3})");
}

TEST(JsonWriter, RefusesAKeyTwiceInOneObject) {
  std::string text;
  JsonWriter in_order(text);
  in_order.BeginObject();
  in_order.Member("a", 1);
  EXPECT_THROW(in_order.Key("a"), std::logic_error);
  text.clear();
  JsonWriter out_of_order(text);
  out_of_order.BeginObject();
  out_of_order.Member("b", 1);
  out_of_order.Member("a", 2);
  out_of_order.Member("b", 3);
  EXPECT_THROW(out_of_order.EndObject(), std::logic_error);
}

TEST(JsonWriter, RefusesValuesAndKeysOutOfPlace) {
  std::string text;
  JsonWriter writer(text);
  writer.BeginObject();
  EXPECT_THROW(writer.Value(1), std::logic_error);  // a member without its key
  writer.Key("a");
  EXPECT_THROW(writer.Key("b"), std::logic_error);     // two keys in a row
  EXPECT_THROW(writer.EndObject(), std::logic_error);  // the key's value is missing
  EXPECT_THROW(writer.EndArray(), std::logic_error);
  writer.Value(1);
  writer.EndObject();
  EXPECT_TRUE(writer.complete());
  EXPECT_THROW(writer.Value(2), std::logic_error);  // a second value at the top
  JsonWriter array(text);
  array.BeginArray();
  EXPECT_THROW(array.Key("a"), std::logic_error);
}

TEST(JsonWriter, RefusesInvalidUtf8AsDumpDoes) {
  std::string text;
  JsonWriter writer(text);
  EXPECT_THROW(writer.Value(std::string("log\xff.clf")), nlohmann::json::type_error);
}

TEST(JsonWriter, Appends) {
  std::string text = "before ";
  JsonWriter writer(text);
  writer.Value(std::vector<int>{1, 2});
  EXPECT_EQ(text, "before [1,2]");
}

}  // namespace
}  // namespace scanloc
