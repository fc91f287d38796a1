// Scoring many postures at once: one widened simulated sweep for headings whole beam steps apart
// must give exactly what scoring each posture on its own gives.

#include <gtest/gtest.h>

#include <cmath>

#include "scanloc/likelihood/posture_scoring.hpp"
#include "scanloc/maps/point_map.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

void ExpectSameScore(const PostureScore& a, const PostureScore& b) {
  ASSERT_EQ(a.simulated.size(), b.simulated.size());
  for (std::size_t k = 0; k < a.simulated.size(); ++k) {
    EXPECT_EQ(a.simulated.IsValid(k), b.simulated.IsValid(k)) << "beam " << k;
    if (a.simulated.IsValid(k)) {
      EXPECT_NEAR(a.simulated.ranges_m[k], b.simulated.ranges_m[k], 1e-9);
    }
  }
  EXPECT_EQ(a.test.valid_pairs, b.test.valid_pairs);
  EXPECT_EQ(a.test.match_pairs, b.test.match_pairs);
  EXPECT_EQ(a.test.histogram, b.test.histogram);
  EXPECT_NEAR(a.test.expect_value_m, b.test.expect_value_m, 1e-12);
  EXPECT_NEAR(a.distance.cost_m2, b.distance.cost_m2, 1e-12);
}

class PostureScoringTest : public ::testing::Test {
 protected:
  LineMap lines_ = testing::Classroom();
  PointMap points_ = PointMapFromLines(lines_, 0.02);
  // A 180° scan of 180 beams, as the benchmark logs: beam steps of 1°.
  LaserScan scan_ = [this] {
    LaserScan scan = testing::NoisyScan(lines_, {2.0, 3.0, 0.3}, 360, 0.01, 7);
    LaserScan half;
    half.layout = scan.layout;
    half.layout.beam_count = 180;
    half.layout.angle_min_rad = -M_PI / 2;
    half.ranges_m.assign(scan.ranges_m.begin(), scan.ranges_m.begin() + 180);
    return half;
  }();
};

TEST_F(PostureScoringTest, HeadingsWholeBeamStepsApartEqualScoringEachAlone) {
  const double step = scan_.layout.angle_increment_rad;
  std::vector<Pose2D> postures;
  for (int s : {0, -5, 5, -10, 10}) postures.push_back({2.02, 2.97, 0.31 + s * step});
  for (const MapView map :
       {MapView{&lines_, nullptr}, MapView{nullptr, &points_}, MapView{&lines_, &points_}}) {
    const auto together = ScorePostures(map, scan_, postures, {});
    ASSERT_EQ(together.size(), postures.size());
    for (std::size_t i = 0; i < postures.size(); ++i)
      ExpectSameScore(together[i], ScorePosture(map, scan_, postures[i], {}));
  }
}

TEST_F(PostureScoringTest, PosturesThatShareNothingAreScoredOneByOne) {
  // Other positions, and a heading that is not a whole number of beam steps away.
  const std::vector<Pose2D> postures{{2.0, 3.0, 0.3}, {2.5, 3.0, 0.3}, {2.0, 3.0, 0.3 + 0.0123}};
  const MapView map{nullptr, &points_};
  const auto together = ScorePostures(map, scan_, postures, {});
  for (std::size_t i = 0; i < postures.size(); ++i)
    ExpectSameScore(together[i], ScorePosture(map, scan_, postures[i], {}));
}

TEST_F(PostureScoringTest, AFullCircleScanIsNotWidenedOntoItself) {
  const LaserScan full = testing::NoisyScan(lines_, {2.0, 3.0, 0.0}, 360, 0.0, 3);
  const double step = full.layout.angle_increment_rad;
  const std::vector<Pose2D> postures{{2.0, 3.0, 0.0}, {2.0, 3.0, 10 * step}};
  const MapView map{&lines_, nullptr};
  const auto together = ScorePostures(map, full, postures, {});
  for (std::size_t i = 0; i < postures.size(); ++i)
    ExpectSameScore(together[i], ScorePosture(map, full, postures[i], {}));
}

}  // namespace
}  // namespace scanloc
