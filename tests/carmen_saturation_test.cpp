#include "scanloc/io/carmen_saturation.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <optional>
#include <random>
#include <vector>

namespace scanloc {
namespace {

// `scans` scans of `beams` beams: far walls between 2 and 30 m from a fixed seed, and every
// `saturated_every`-th beam (0: none) reporting one of `codes` in turn.
std::vector<BeamReading> Scans(std::size_t scans, std::size_t beams, std::size_t saturated_every,
                               const std::vector<double>& codes = {}) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> wall_m(2.0, 30.0);
  std::vector<BeamReading> readings;
  std::size_t code = 0;
  for (std::size_t s = 0; s < scans; ++s)
    for (std::size_t b = 0; b < beams; ++b) {
      const bool saturated = saturated_every > 0 && b % saturated_every == 0;
      readings.push_back({saturated ? codes[code++ % codes.size()] : wall_m(rng), b});
    }
  return readings;
}

TEST(RecogniseSaturation, FindsAJitteringCodeLikeOrebrosAndReturnsItsLowestValue) {
  const auto readings = Scans(50, 181, 7, {32.767, 32.763, 32.767, 32.759});
  const std::optional<double> code_m = RecogniseSaturation(readings);
  ASSERT_TRUE(code_m.has_value());
  EXPECT_NEAR(*code_m, 32.759, 1e-12);
}

TEST(RecogniseSaturation, FindsAOneValueCodeLikeIntelsAboveFarReadings) {
  auto readings = Scans(20, 180, 4, {81.83});
  readings.push_back({40.5, 3});  // a far wall well below the code
  const std::optional<double> code_m = RecogniseSaturation(readings);
  ASSERT_TRUE(code_m.has_value());
  EXPECT_NEAR(*code_m, 81.83, 1e-12);
}

TEST(RecogniseSaturation, AMaximumReadOnceOrTwiceIsAFarWallNotACode) {
  auto readings = Scans(50, 181, 0);
  readings.push_back({45.0, 90});
  readings.push_back({45.0, 91});
  EXPECT_FALSE(RecogniseSaturation(readings).has_value());
}

TEST(RecogniseSaturation, AFarWallRepeatedAtTheSameBeamsWhileStandingStillIsNotACode) {
  auto readings = Scans(100, 181, 0);
  for (std::size_t s = 0; s < 100; ++s) {  // 200 identical readings, on two beams only
    readings.push_back({35.0, 40});
    readings.push_back({35.0, 41});
  }
  EXPECT_FALSE(RecogniseSaturation(readings).has_value());
}

TEST(RecogniseSaturation, ATopBandNoDenserThanTheMetreBelowItIsNotACode) {
  // A far surface read over many beams and ranges: 116 readings on many beams in the 0.035 m band
  // at the top, enough for a code, but 3,184 in the metre below.
  std::vector<BeamReading> readings;
  for (std::size_t i = 0; i < 3300; ++i) readings.push_back({35.0 - i / 3300.0, i % 181});
  EXPECT_FALSE(RecogniseSaturation(readings).has_value());
}

TEST(RecogniseSaturation, IgnoresNonFiniteAndNonPositiveReadings) {
  std::vector<BeamReading> readings = {{NAN, 0}, {INFINITY, 1}, {-1.0, 2}, {0.0, 3}};
  EXPECT_FALSE(RecogniseSaturation(readings).has_value());
  EXPECT_FALSE(RecogniseSaturation({}).has_value());
  auto saturated = Scans(20, 180, 4, {81.83});
  saturated.push_back({INFINITY, 5});
  ASSERT_TRUE(RecogniseSaturation(saturated).has_value());
  EXPECT_NEAR(*RecogniseSaturation(saturated), 81.83, 1e-12);
}

}  // namespace
}  // namespace scanloc
