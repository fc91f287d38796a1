#include <gtest/gtest.h>

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <cstring>
#include <string>

#include "scanloc/common/parse_error.hpp"

namespace scanloc {
namespace {

// What ParseDouble promises: strtod's value for every field strtod takes whole without
// overflowing, and a ParseError naming the file, line and field otherwise.
double Strtod(const std::string& field) {
  return std::strtod(field.c_str(), nullptr);
}

TEST(ParseDouble, GivesStrtodsValueBitForBitOnTheFieldsStrtodTakes) {
  for (const std::string field : {"0",
                                  "-0",
                                  "46.56",
                                  "81.83",
                                  "-3.1415926535897931",
                                  "1e-5",
                                  "1E+3",
                                  "+1.5",
                                  "+.5",
                                  ".25",
                                  "5.",
                                  "0x1p-3",
                                  "0X1.8P1",
                                  "inf",
                                  "-Infinity",
                                  "1e-400",
                                  "4.9406564584124654e-324",
                                  "1.7976931348623157e308",
                                  "976052857.33753",
                                  "0.10000000000000000555",
                                  "123456789012345678901234567890"}) {
    const double parsed = ParseDouble(field, "log.clf", 7, "a range");
    const double expected = Strtod(field);
    EXPECT_EQ(std::memcmp(&parsed, &expected, sizeof parsed), 0) << field;
  }
  EXPECT_TRUE(std::isnan(ParseDouble("nan", "log.clf", 7, "a range")));
}

TEST(ParseDouble, RefusesWhatIsNotOneWholeNumberNamingTheFileLineAndField) {
  for (const std::string field : {"", "1.5x", "x1", "1,5", "--1", "1e500", "-1e500", "0x"}) {
    try {
      ParseDouble(field, "log.clf", 7, "a range");
      ADD_FAILURE() << "accepted '" << field << "'";
    } catch (const ParseError& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("log.clf"), std::string::npos) << message;
      EXPECT_NE(message.find('7'), std::string::npos) << message;
      EXPECT_NE(message.find("expected a range, got '" + field + "'"), std::string::npos)
          << message;
    }
  }
}

}  // namespace
}  // namespace scanloc
