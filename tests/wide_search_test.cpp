// The wide search: it finds a known posture from a displaced window centre, its branch and bound
// returns the same best score as scoring every posture, and degenerate inputs give no candidate.

#include "scanloc/session/wide_search.hpp"

#include <gtest/gtest.h>

#include <cmath>

#include "scanloc/maps/line_map.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

class WideSearchTest : public ::testing::Test {
 protected:
  WideSearchTest()
      : room_(testing::SmallRoomWithL()),
        truth_{3.0, 2.5, 0.3},
        scan_(testing::NoisyScan(room_, truth_, 720, 0.01, 11)) {}

  LineMap room_;
  Pose2D truth_;
  LaserScan scan_;
};

TEST_F(WideSearchTest, FindsTheTruePostureFromACentre0_6mAnd12DegreesOff) {
  const SearchWindow window{
      {truth_.x_m + 0.45, truth_.y_m - 0.4, truth_.yaw_rad + 0.21}, 1.0, 0.35};
  const WideSearchResult result = WideSearch({&room_, nullptr}, scan_, window);
  ASSERT_FALSE(result.candidates.empty());
  const Pose2D& best = result.candidates.front().T_world_laser;
  // Within one cell (0.05 m) and one heading step of the truth.
  EXPECT_NEAR(best.x_m, truth_.x_m, 0.05);
  EXPECT_NEAR(best.y_m, truth_.y_m, 0.05);
  EXPECT_NEAR(NormalizeAngle(best.yaw_rad - truth_.yaw_rad), 0.0, 0.02);
  EXPECT_GT(result.candidates.front().score, 0.5);
  EXPECT_GT(result.headings, 40);
}

TEST_F(WideSearchTest, BranchAndBoundMatchesScoringEveryPosture) {
  const SearchWindow window{{truth_.x_m + 0.2, truth_.y_m + 0.15, truth_.yaw_rad - 0.05}, 0.4, 0.1};
  WideSearchOptions exhaustive;
  exhaustive.field.levels = 1;  // no coarser level: every posture is a root and a leaf
  exhaustive.max_candidates = 1;
  WideSearchOptions bounded = exhaustive;
  bounded.field.levels = 6;
  const WideSearchResult all = WideSearch({&room_, nullptr}, scan_, window, exhaustive);
  const WideSearchResult pruned = WideSearch({&room_, nullptr}, scan_, window, bounded);
  ASSERT_EQ(all.candidates.size(), 1u);
  ASSERT_EQ(pruned.candidates.size(), 1u);
  EXPECT_FLOAT_EQ(static_cast<float>(pruned.candidates[0].score),
                  static_cast<float>(all.candidates[0].score));
  EXPECT_LT(pruned.nodes_scored, all.nodes_scored / 4);  // and it pruned most of them
}

TEST_F(WideSearchTest, DistinctCandidatesAreApartByTheSeparation) {
  WideSearchOptions options;
  options.max_candidates = 4;
  const SearchWindow window{truth_, 1.5, 0.5};
  const WideSearchResult result = WideSearch({&room_, nullptr}, scan_, window, options);
  ASSERT_GE(result.candidates.size(), 2u);
  for (std::size_t i = 0; i < result.candidates.size(); ++i)
    for (std::size_t j = i + 1; j < result.candidates.size(); ++j) {
      const Pose2D& a = result.candidates[i].T_world_laser;
      const Pose2D& b = result.candidates[j].T_world_laser;
      // 1e-9: a separation of exactly the minimum is distinct, up to rounding.
      EXPECT_TRUE(std::hypot(a.x_m - b.x_m, a.y_m - b.y_m) >= options.min_separation_m - 1e-9 ||
                  std::abs(NormalizeAngle(a.yaw_rad - b.yaw_rad)) >=
                      options.min_separation_rad - 1e-9)
          << i << " " << j << ": " << a.x_m - b.x_m << " " << a.y_m - b.y_m << " "
          << a.yaw_rad - b.yaw_rad;
      EXPECT_GE(result.candidates[i].score, result.candidates[j].score);
    }
}

TEST_F(WideSearchTest, SkippingBlocksThatKeptBetterPosturesShadowChangesNoCandidateAndScoresFewer) {
  // Several distinct candidates from wide windows around the room: the pool's threshold stays
  // low, so the slopes of the best peaks are searched and blocks on them are shadowed.
  int shadowed_searches = 0;
  for (const SearchWindow& window :
       {SearchWindow{truth_, 1.5, 0.5}, SearchWindow{{2.0, 3.0, 1.2}, 2.0, 3.2},
        SearchWindow{{4.0, 2.0, -0.4}, 1.0, 0.3}}) {
    WideSearchOptions skipping;
    skipping.max_candidates = 6;
    WideSearchOptions searching = skipping;
    searching.skip_shadowed_blocks = false;
    const WideSearchResult fewer = WideSearch({&room_, nullptr}, scan_, window, skipping);
    const WideSearchResult all = WideSearch({&room_, nullptr}, scan_, window, searching);
    ASSERT_EQ(fewer.candidates.size(), all.candidates.size());
    for (std::size_t i = 0; i < all.candidates.size(); ++i) {
      const Pose2D& a = fewer.candidates[i].T_world_laser;
      const Pose2D& b = all.candidates[i].T_world_laser;
      EXPECT_TRUE(a.x_m == b.x_m && a.y_m == b.y_m && a.yaw_rad == b.yaw_rad) << i;
      EXPECT_EQ(fewer.candidates[i].score, all.candidates[i].score) << i;
    }
    EXPECT_LE(fewer.nodes_scored, all.nodes_scored);
    shadowed_searches += fewer.nodes_scored < all.nodes_scored;
  }
  EXPECT_EQ(shadowed_searches, 3);
}

TEST_F(WideSearchTest, AnEmptyMapOrAScanWithoutEchoGivesNoCandidate) {
  const SearchWindow window{truth_, 1.0, 0.3};
  EXPECT_TRUE(WideSearch({nullptr, nullptr}, scan_, window).candidates.empty());
  LaserScan blind = scan_;
  for (double& r : blind.ranges_m) r = -1.0;
  EXPECT_TRUE(WideSearch({&room_, nullptr}, blind, window).candidates.empty());
}

TEST_F(WideSearchTest, ANegativeWindowIsRefused) {
  EXPECT_THROW(WideSearch({&room_, nullptr}, scan_, {truth_, -1.0, 0.3}), std::invalid_argument);
}

}  // namespace
}  // namespace scanloc
