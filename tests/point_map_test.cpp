#include "scanloc/maps/point_map.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <random>
#include <set>
#include <utility>
#include <vector>

#include "scanloc/maps/line_map.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

using Neighbours = std::vector<std::pair<std::uint32_t, double>>;

constexpr double kTight = 1e-12;

PointMapOptions KeepEveryPoint() {
  PointMapOptions options;
  options.cell_size_m = 0.0;
  return options;
}

std::vector<Eigen::Vector2d> RandomPoints(std::size_t count, double half_extent_m,
                                          std::mt19937& rng) {
  std::uniform_real_distribution<double> coordinate(-half_extent_m, half_extent_m);
  std::vector<Eigen::Vector2d> points(count);
  for (auto& p : points) p = {coordinate(rng), coordinate(rng)};
  return points;
}

// The oracles: every stored point examined, no index.
Neighbours BruteForceRadius(const PointMap& map, const Eigen::Vector2d& centre, double radius_m) {
  Neighbours found;
  for (std::size_t i = 0; i < map.size(); ++i) {
    const double squared = (map.point(i) - centre).squaredNorm();
    if (squared < radius_m * radius_m) found.emplace_back(static_cast<std::uint32_t>(i), squared);
  }
  return found;
}

Neighbours BruteForceKNearest(const PointMap& map, const Eigen::Vector2d& centre, std::size_t k) {
  Neighbours all;
  for (std::size_t i = 0; i < map.size(); ++i)
    all.emplace_back(static_cast<std::uint32_t>(i), (map.point(i) - centre).squaredNorm());
  k = std::min(k, all.size());
  std::partial_sort(all.begin(), all.begin() + k, all.end(), [](const auto& a, const auto& b) {
    return a.second != b.second ? a.second < b.second : a.first < b.first;
  });
  all.resize(k);
  return all;
}

void ExpectSameNeighbours(Neighbours indexed, Neighbours brute_force, const std::string& what) {
  std::sort(indexed.begin(), indexed.end());
  std::sort(brute_force.begin(), brute_force.end());
  ASSERT_EQ(indexed.size(), brute_force.size()) << what;
  for (std::size_t i = 0; i < indexed.size(); ++i) {
    ASSERT_EQ(indexed[i].first, brute_force[i].first) << what << ", neighbour " << i;
    ASSERT_NEAR(indexed[i].second, brute_force[i].second, kTight) << what << ", neighbour " << i;
  }
}

// Random radius and k-nearest queries over the whole map, each checked against brute force.
void ExpectQueriesMatchBruteForce(const PointMap& map, double half_extent_m, std::mt19937& rng,
                                  int query_count) {
  std::uniform_real_distribution<double> coordinate(-1.2 * half_extent_m, 1.2 * half_extent_m);
  std::uniform_real_distribution<double> radius(0.01 * half_extent_m, 0.5 * half_extent_m);
  // Every fifth query covers the whole map (as a long-range simulated scan does), which lists the
  // points without the tree.
  std::uniform_real_distribution<double> covering(3.2 * half_extent_m, 4.0 * half_extent_m);
  // And every fifth is short (as the refinement's line fits), which the search grid answers.
  std::uniform_real_distribution<double> short_radius(0.05, 0.8);
  // The last k asks for more than the map holds when the map is small.
  const std::size_t ks[] = {1, 2, 7, 40, 250, std::min<std::size_t>(map.size() + 3, 1003)};
  for (int q = 0; q < query_count; ++q) {
    const Eigen::Vector2d centre(coordinate(rng), coordinate(rng));
    const double radius_m =
        q % 5 == 4 ? covering(rng) : (q % 5 == 2 ? short_radius(rng) : radius(rng));
    const std::string where = "map of " + std::to_string(map.size()) + " points, query " +
                              std::to_string(q) + " at (" + std::to_string(centre.x()) + ", " +
                              std::to_string(centre.y()) + ")";
    ExpectSameNeighbours(map.RadiusSearch(centre, radius_m),
                         BruteForceRadius(map, centre, radius_m),
                         where + ", radius " + std::to_string(radius_m));
    const std::size_t k = ks[q % std::size(ks)];
    const Neighbours indexed = map.KNearest(centre, k);
    const Neighbours brute_force = BruteForceKNearest(map, centre, k);
    ASSERT_EQ(indexed.size(), brute_force.size()) << where << ", k " << k;
    for (std::size_t i = 0; i < indexed.size(); ++i) {
      // Nearest first; random coordinates leave no ties.
      ASSERT_EQ(indexed[i].first, brute_force[i].first) << where << ", k " << k << ", rank " << i;
      ASSERT_NEAR(indexed[i].second, brute_force[i].second, kTight) << where << ", rank " << i;
    }
  }
}

TEST(PointMapDeduplicationTest, PointsInOneCellMergeIntoTheirMeanWithTheSmallerSpacing) {
  PointMapOptions options;
  options.cell_size_m = 0.05;
  PointMap map(options);
  EXPECT_TRUE(map.Insert({0.01, 0.01}, 0.2));
  EXPECT_FALSE(map.Insert({0.04, 0.02}, 0.1));
  EXPECT_FALSE(map.Insert({0.03, 0.049}, 0.25));
  ASSERT_EQ(map.size(), 1u);
  // The kept point is the mean of the three samples.
  EXPECT_NEAR(map.point(0).x(), (0.01 + 0.04 + 0.03) / 3.0, 1e-12);
  EXPECT_NEAR(map.point(0).y(), (0.01 + 0.02 + 0.049) / 3.0, 1e-12);
  EXPECT_DOUBLE_EQ(map.spacing(0), 0.1);
}

TEST(PointMapDeduplicationTest, SamplesWithinACellDiagonalMergeAcrossCellsIncludingZero) {
  PointMapOptions options;
  options.cell_size_m = 0.05;  // diagonal 0.0707 m
  PointMap map(options);
  EXPECT_TRUE(map.Insert({0.01, 0.01}, 0.1));
  EXPECT_TRUE(map.Insert({0.12, 0.01}, 0.1));  // 11 cm away: a new point
  EXPECT_TRUE(map.Insert({0.01, 0.09}, 0.1));
  EXPECT_TRUE(map.Insert({-0.07, 0.01}, 0.1));    // across zero (floor, not truncation)
  EXPECT_FALSE(map.Insert({0.055, 0.01}, 0.1));   // another cell, 4.5 cm from the first: merged
  EXPECT_FALSE(map.Insert({-0.01, -0.01}, 0.1));  // cell (-1, -1), 2.8 cm from the first: merged
  EXPECT_EQ(map.size(), 4u);
  // The first point is now the mean of its three samples.
  EXPECT_NEAR(map.point(0).x(), (0.01 + 0.055 - 0.01) / 3.0, 1e-12);
}

TEST(PointMapDeduplicationTest, BatchInsertDeduplicatesWithinTheBatchAndCountsAdded) {
  PointMapOptions options;
  options.cell_size_m = 0.5;
  options.max_point_spacing_m = 1.0;
  PointMap map(options);
  const std::vector<Eigen::Vector2d> points = {{0.1, 0.1}, {0.2, 0.3}, {1.0, 0.1}, {0.9, 0.4}};
  EXPECT_EQ(map.Insert(points, {0.9, 0.6, 0.6, 0.55}), 2u);
  ASSERT_EQ(map.size(), 2u);
  EXPECT_DOUBLE_EQ(map.spacing(0), 0.6);
  EXPECT_DOUBLE_EQ(map.spacing(1), 0.55);
}

TEST(PointMapDeduplicationTest, ZeroCellSizeKeepsEveryPointEvenCoincidentOnes) {
  PointMap map(KeepEveryPoint());
  for (int i = 0; i < 3; ++i) EXPECT_TRUE(map.Insert({1.0, 2.0}, 0.1));
  EXPECT_TRUE(map.Insert({1.001, 2.0}, 0.1));
  EXPECT_EQ(map.size(), 4u);
}

TEST(PointMapInsertTest, RecordedSpacingIsBoundedByCellSizeAndMaxPointSpacing) {
  PointMapOptions options;
  options.cell_size_m = 0.05;
  options.max_point_spacing_m = 0.3;
  PointMap map(options);
  map.Insert({0.0, 0.0}, 0.01);
  map.Insert({1.0, 0.0}, 7.0);
  map.Insert({2.0, 0.0}, 0.2);
  ASSERT_EQ(map.size(), 3u);
  EXPECT_DOUBLE_EQ(map.spacing(0), 0.05);
  EXPECT_DOUBLE_EQ(map.spacing(1), 0.3);
  EXPECT_DOUBLE_EQ(map.spacing(2), 0.2);
}

TEST(PointMapInsertTest, NonFinitePointsAreSkipped) {
  PointMap map;
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  EXPECT_EQ(map.Insert({{nan, 0.0}, {1.0, inf}, {1.0, 1.0}}, {0.1, 0.1, 0.1}), 1u);
  EXPECT_FALSE(map.Insert({nan, nan}, 0.1));
  EXPECT_EQ(map.size(), 1u);
}

TEST(PointMapInsertTest, MismatchedSpacingCountThrowsInvalidArgument) {
  PointMap map;
  const std::vector<Eigen::Vector2d> two_points = {{0.0, 0.0}, {1.0, 1.0}};
  EXPECT_THROW(map.Insert(two_points, {0.1}), std::invalid_argument);
  EXPECT_TRUE(map.empty());
}

TEST(PointMapInsertTest, InsertScanPlacesValidBeamsAtClosedFormWorldPoints) {
  // (3.6) x_k = x + r_k·cos(θ + θ_min + k·Δθ), y_k = y + r_k·sin(θ + θ_min + k·Δθ).
  PointMapOptions options = KeepEveryPoint();
  options.max_point_spacing_m = 100.0;  // no clamping: the spacings below are checked exactly
  PointMap map(options);
  LaserScan scan;
  scan.layout = MakeLayout(9, M_PI / 2.0, 10.0);
  const double nan = std::numeric_limits<double>::quiet_NaN();
  scan.ranges_m = {3.0, 3.0, -1.0, 4.0, nan, 12.0, 5.0, 5.0, 2.0};
  const Pose2D T_world_laser(2.0, -1.0, 0.7);
  ASSERT_EQ(map.InsertScan(scan, T_world_laser), 6u);

  const double increment_rad = M_PI / 16.0;
  const double first_bearing_rad = 0.7 - M_PI / 4.0;
  const std::size_t valid_beams[] = {0, 1, 3, 6, 7, 8};
  // Chord between equal ranges r: 2r·sin(Δθ/2); between r1 and r2: law of cosines; an isolated
  // beam: r·Δθ.
  const double chord_3 = 2.0 * 3.0 * std::sin(increment_rad / 2.0);
  const double chord_5 = 2.0 * 5.0 * std::sin(increment_rad / 2.0);
  const double gap_5_2 = std::sqrt(25.0 + 4.0 - 2.0 * 5.0 * 2.0 * std::cos(increment_rad));
  const double expected_spacing[] = {
      chord_3, chord_3, 4.0 * increment_rad, chord_5, std::min(chord_5, gap_5_2), gap_5_2};
  ASSERT_EQ(map.size(), std::size(valid_beams));
  for (std::size_t i = 0; i < map.size(); ++i) {
    const std::size_t k = valid_beams[i];
    const double r = scan.ranges_m[k];
    const double angle = first_bearing_rad + k * increment_rad;
    EXPECT_NEAR(map.point(i).x(), 2.0 + r * std::cos(angle), kTight) << "beam " << k;
    EXPECT_NEAR(map.point(i).y(), -1.0 + r * std::sin(angle), kTight) << "beam " << k;
    EXPECT_NEAR(map.spacing(i), expected_spacing[i], kTight) << "beam " << k;
  }
}

TEST(PointMapOptionsTest, InvalidOptionsThrowInvalidArgument) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  for (const double cell_size_m : {-0.01, nan, inf}) {
    PointMapOptions options;
    options.cell_size_m = cell_size_m;
    EXPECT_THROW(PointMap{options}, std::invalid_argument) << "cell_size_m " << cell_size_m;
  }
  for (const double max_spacing_m : {0.0, -1.0, nan, inf}) {
    PointMapOptions options;
    options.max_point_spacing_m = max_spacing_m;
    EXPECT_THROW(PointMap{options}, std::invalid_argument)
        << "max_point_spacing_m " << max_spacing_m;
  }
}

TEST(PointMapQueryTest, EmptyMapZeroRadiusAndZeroKReturnNothing) {
  PointMap empty_map;
  EXPECT_TRUE(empty_map.RadiusSearch({0.0, 0.0}, 10.0).empty());
  EXPECT_TRUE(empty_map.KNearest({0.0, 0.0}, 3).empty());
  PointMap map;
  map.Insert({0.0, 0.0}, 0.1);
  EXPECT_TRUE(map.RadiusSearch({0.0, 0.0}, 0.0).empty());
  EXPECT_TRUE(map.KNearest({0.0, 0.0}, 0).empty());
}

class PointMapQueryOracleTest : public ::testing::TestWithParam<std::size_t> {};

TEST_P(PointMapQueryOracleTest, RadiusSearchAndKNearestEqualBruteForce) {
  const std::size_t count = GetParam();
  std::mt19937 rng(20240601u + static_cast<unsigned>(count));
  const double half_extent_m = 50.0;
  PointMap map(KeepEveryPoint());
  ASSERT_EQ(map.Insert(RandomPoints(count, half_extent_m, rng), std::vector<double>(count, 0.1)),
            count);
  ExpectQueriesMatchBruteForce(map, half_extent_m, rng, 30);
}

INSTANTIATE_TEST_SUITE_P(Sizes, PointMapQueryOracleTest, ::testing::Values(1, 10, 1000, 50000),
                         [](const auto& test_info) {
                           return "points_" + std::to_string(test_info.param);
                         });

TEST(PointMapQueryTest, IncrementalBatchesAndSingleInsertsMatchBruteForceAfterEachStep) {
  std::mt19937 rng(7u);
  const double half_extent_m = 50.0;
  PointMapOptions options;
  options.cell_size_m = 0.05;  // some of the 50,000 points share a cell at this density
  PointMap map(options);
  std::set<std::pair<std::int64_t, std::int64_t>> occupied_cells;
  const auto cell_of = [&](const Eigen::Vector2d& p) {
    return std::make_pair(static_cast<std::int64_t>(std::floor(p.x() / options.cell_size_m)),
                          static_cast<std::int64_t>(std::floor(p.y() / options.cell_size_m)));
  };
  for (int i = 0; i < 5; ++i) {
    const Eigen::Vector2d p = RandomPoints(1, half_extent_m, rng).front();
    EXPECT_EQ(map.Insert(p, 0.1), occupied_cells.insert(cell_of(p)).second);
    ExpectQueriesMatchBruteForce(map, half_extent_m, rng, 3);
  }
  for (const std::size_t batch : {1, 9, 90, 900, 9000, 39995}) {
    const auto points = RandomPoints(batch, half_extent_m, rng);
    for (const auto& p : points) occupied_cells.insert(cell_of(p));
    map.Insert(points, std::vector<double>(batch, 0.1));
    // At most one point per occupied cell: a sample within a diagonal of another merges.
    ASSERT_LE(map.size(), occupied_cells.size()) << "after a batch of " << batch;
    ASSERT_GT(map.size(), 0.9 * occupied_cells.size()) << "after a batch of " << batch;
    ExpectQueriesMatchBruteForce(map, half_extent_m, rng, 10);
  }
  EXPECT_LT(map.size(), 50000u);  // the grid did merge some
}

TEST(PointMapFromLinesTest, SamplesIncludeVerticesWithGapsAtMostTheRequestedSpacing) {
  LineMap lines = testing::RectangleRoom(4.0, 3.0);
  lines.segments.push_back({{0.5, 0.5}, {3.1, 2.2}});  // a diagonal, length not a multiple
  const double spacing_m = 0.23;
  const PointMap map = PointMapFromLines(lines, spacing_m);  // default 0.05 m de-duplication

  std::vector<Eigen::Vector2d> points(map.size());
  for (std::size_t i = 0; i < map.size(); ++i) {
    points[i] = map.point(i);
    EXPECT_DOUBLE_EQ(map.spacing(i), spacing_m);
  }
  const auto nearest_distance = [&](const Eigen::Vector2d& q) {
    double best = std::numeric_limits<double>::infinity();
    for (const auto& p : points) best = std::min(best, (p - q).norm());
    return best;
  };
  for (const Segment& segment : lines.segments) {
    EXPECT_LT(nearest_distance(segment.a), kTight);
    EXPECT_LT(nearest_distance(segment.b), kTight);
    // The samples on this segment, ordered along it, are never further apart than requested.
    const Eigen::Vector2d direction = (segment.b - segment.a) / segment.Length();
    std::vector<double> along_m;
    for (const auto& p : points) {
      const Eigen::Vector2d w = p - segment.a;
      const double t = w.dot(direction);
      if (std::abs(w.x() * direction.y() - w.y() * direction.x()) < 1e-9 && t > -1e-9 &&
          t < segment.Length() + 1e-9)
        along_m.push_back(t);
    }
    std::sort(along_m.begin(), along_m.end());
    ASSERT_GE(along_m.size(), 2u);
    EXPECT_NEAR(along_m.front(), 0.0, kTight);
    EXPECT_NEAR(along_m.back(), segment.Length(), 1e-9);
    for (std::size_t i = 1; i < along_m.size(); ++i)
      EXPECT_LE(along_m[i] - along_m[i - 1], spacing_m + 1e-9) << "gap " << i;
  }
  // Every sample lies on a segment.
  for (const auto& p : points) {
    bool on_a_segment = false;
    for (const Segment& segment : lines.segments) {
      const Eigen::Vector2d d = segment.b - segment.a;
      const double t = std::clamp((p - segment.a).dot(d) / d.squaredNorm(), 0.0, 1.0);
      on_a_segment = on_a_segment || (segment.a + t * d - p).norm() < 1e-9;
    }
    EXPECT_TRUE(on_a_segment) << p.transpose();
  }
}

TEST(PointMapOptions, OptionsDifferingInAnyOneFieldCompareUnequal) {
  const PointMapOptions base;
  PointMapOptions cell = base;
  cell.cell_size_m += 0.01;
  PointMapOptions spacing = base;
  spacing.max_point_spacing_m += 0.01;
  EXPECT_EQ(base, PointMapOptions{});
  EXPECT_NE(base, cell);
  EXPECT_NE(base, spacing);
}

}  // namespace
}  // namespace scanloc
