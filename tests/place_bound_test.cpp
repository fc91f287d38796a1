#include "scanloc/session/place_bound.hpp"

#include <gtest/gtest.h>

#include <stdexcept>

namespace scanloc {
namespace {

// Two places 20 m apart: around (0, 0) the map fits its scans at 0.06–0.08 m, around (20, 0) at
// 0.11–0.14 m (walls laid twice); the map's median is 0.08 m.
std::vector<MapSignatureSample> TwoPlaces() {
  return {{0.0, 0.0, 0.06},  {0.5, 0.0, 0.07},  {1.0, 0.0, 0.08},  {0.0, 0.5, 0.07},
          {0.5, 0.5, 0.06},  {20.0, 0.0, 0.12}, {20.5, 0.0, 0.14}, {21.0, 0.0, 0.11},
          {20.0, 0.5, 0.13}, {20.5, 0.5, 0.12}};
}

TEST(PlaceBound, RaisesThePriorByHowMuchTheNearestSamplesMedianExceedsTheMapsMedian) {
  const PlaceBound bound(TwoPlaces(), 0.08);
  // Around (20, 0): the five nearest have median 0.12 m, 0.04 m above the map's median.
  EXPECT_NEAR(bound.Excess(Pose2D(20.3, 0.2, 1.0)), 0.04, 1e-12);
  EXPECT_NEAR(bound.At(Pose2D(20.3, 0.2, 1.0), 0.15), 0.19, 1e-12);
  // Around (0, 0) the map fits better than its median: the prior stands, never lowered.
  EXPECT_DOUBLE_EQ(bound.Excess(Pose2D(0.3, 0.2, 0.0)), 0.0);
  EXPECT_DOUBLE_EQ(bound.At(Pose2D(0.3, 0.2, 0.0), 0.15), 0.15);
  // Three neighbours: the median of 0.12, 0.13, 0.12 at (20.2, 0.3).
  EXPECT_NEAR(PlaceBound(TwoPlaces(), 0.08, 3).Excess(Pose2D(20.2, 0.3, 0.0)), 0.04, 1e-12);
  // An even count takes the middle two's mean: at (20.9, 0.0) the nearest are 0.11 and 0.14.
  EXPECT_NEAR(PlaceBound(TwoPlaces(), 0.08, 2).Excess(Pose2D(20.9, 0.0, 0.0)), 0.045, 1e-12);
}

TEST(PlaceBound, WithoutSamplesEveryPlaceHasThePriorAndBadArgumentsAreRefused) {
  const PlaceBound none;
  EXPECT_TRUE(none.empty());
  EXPECT_DOUBLE_EQ(none.At(Pose2D(20.0, 0.0, 0.0), 0.13), 0.13);
  // Fewer samples than neighbours: all of them.
  EXPECT_NEAR(PlaceBound({{0.0, 0.0, 0.2}}, 0.08).Excess(Pose2D(50.0, 0.0, 0.0)), 0.12, 1e-12);
  EXPECT_THROW(PlaceBound(TwoPlaces(), 0.08, 0), std::invalid_argument);
  EXPECT_THROW(PlaceBound(TwoPlaces(), std::nan("")), std::invalid_argument);
}

}  // namespace
}  // namespace scanloc
