#include "refinement/point_line_fit.hpp"

#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <random>
#include <vector>

#include "scanloc/maps/point_map.hpp"

namespace scanloc {
namespace {

// Walls with a corner, a door gap and a pillar, sampled every 3 cm by three noisy passes
// (σ = 1 cm, seed 7): merged samples move the points' means off their cells.
PointMap NoisyRoom() {
  PointMap map;
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 0.01);
  std::vector<Eigen::Vector2d> points;
  const auto wall = [&](Eigen::Vector2d a, Eigen::Vector2d b) {
    const int n = static_cast<int>((b - a).norm() / 0.03);
    for (int i = 0; i <= n; ++i)
      points.push_back(a + (b - a) * (static_cast<double>(i) / n) +
                       Eigen::Vector2d(noise(rng), noise(rng)));
  };
  for (int pass = 0; pass < 3; ++pass) {
    wall({0.0, 0.0}, {6.0, 0.0});
    wall({6.0, 0.0}, {6.0, 4.0});
    wall({6.0, 4.0}, {3.5, 4.0});
    wall({2.5, 4.0}, {0.0, 4.0});  // a door between x = 2.5 and 3.5
    wall({0.0, 4.0}, {0.0, 0.0});
    for (int a = 0; a < 40; ++a) {  // a round pillar of radius 0.2 m at (3, 2)
      const double t = 2.0 * M_PI * a / 40.0;
      points.push_back(Eigen::Vector2d(3.0 + 0.2 * std::cos(t), 2.0 + 0.2 * std::sin(t)) +
                       Eigen::Vector2d(noise(rng), noise(rng)));
    }
  }
  map.Insert(points, std::vector<double>(points.size(), 0.03));
  return map;
}

// The reference: every map point within the radius, sorted by distance (ties by index), the
// first k, their centroid and spread summed nearest first, the spread's minor axis as normal.
bool BruteForceLine(const PointMap& map, const Eigen::Vector2d& query,
                    const PointLineFitOptions& options, SurfaceLine& line) {
  std::vector<std::pair<double, std::size_t>> within;
  for (std::size_t i = 0; i < map.size(); ++i) {
    const double d2 = (map.point(i) - query).squaredNorm();
    if (d2 < options.radius_m * options.radius_m) within.emplace_back(d2, i);
  }
  std::sort(within.begin(), within.end());
  within.resize(std::min(within.size(), static_cast<std::size_t>(options.neighbours)));
  if (within.size() < 2) return false;
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const auto& [d2, i] : within) centroid += map.point(i);
  centroid /= static_cast<double>(within.size());
  Eigen::Matrix2d spread = Eigen::Matrix2d::Zero();
  for (const auto& [d2, i] : within)
    spread += (map.point(i) - centroid) * (map.point(i) - centroid).transpose();
  const SpreadAxes axes = SymmetricEigen2(spread(0, 0), spread(0, 1), spread(1, 1));
  if (!(axes.largest > 0.0) ||
      std::sqrt(std::max(0.0, axes.smallest) / axes.largest) > options.max_thickness)
    return false;
  line.normal = axes.minor_axis;
  line.offset = line.normal.dot(centroid);
  return true;
}

// The closed form against Eigen's iterative solver, on spreads of a few points along random
// lines, thin to round, at scales from a millimetre to a kilometre, and on diagonal matrices.
TEST(SymmetricEigen2, AgreesWithEigensSolverFromThinToRoundSpreads) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), unit(0.0, 1.0);
  int checked = 0;
  for (int i = 0; i < 20000; ++i) {
    const double theta = angle(rng), scale = std::pow(10.0, -3.0 + 6.0 * unit(rng));
    const double thickness = std::pow(10.0, -8.0 * unit(rng)) * 0.9;  // λmin/λmax up to 0.81
    const Eigen::Vector2d major(std::cos(theta), std::sin(theta)), minor(-major.y(), major.x());
    Eigen::Matrix2d m =
        scale * (major * major.transpose() + thickness * thickness * minor * minor.transpose());
    if (i % 100 == 0) m = Eigen::Vector2d(scale, thickness * scale).asDiagonal();
    const SpreadAxes axes = SymmetricEigen2(m(0, 0), m(0, 1), m(1, 1));
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(m);
    const double largest = eigen.eigenvalues()(1);
    ASSERT_NEAR(axes.largest, largest, 1e-13 * largest) << i;
    ASSERT_NEAR(axes.smallest, eigen.eigenvalues()(0), 1e-13 * largest) << i;
    ASSERT_NEAR(axes.minor_axis.norm(), 1.0, 1e-14) << i;
    // Either sign; an axis good to rounding relative to the eigenvalues' gap.
    const double gap = (largest - eigen.eigenvalues()(0)) / largest;
    ASSERT_NEAR(std::abs(axes.minor_axis.dot(eigen.eigenvectors().col(0))), 1.0, 1e-13 / gap) << i;
    ++checked;
  }
  EXPECT_EQ(checked, 20000);
  // A multiple of the identity (a single point, a circle): both equal, any unit axis.
  const SpreadAxes round = SymmetricEigen2(2.0, 0.0, 2.0);
  EXPECT_EQ(round.smallest, 2.0);
  EXPECT_EQ(round.largest, 2.0);
  EXPECT_DOUBLE_EQ(round.minor_axis.norm(), 1.0);
  const SpreadAxes zero = SymmetricEigen2(0.0, 0.0, 0.0);
  EXPECT_EQ(zero.largest, 0.0);
}

TEST(FitPointLine, IsTheLineThroughTheKNearestWithinTheRadiusFoundByBruteForce) {
  const PointMap map = NoisyRoom();
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> room_x(-0.3, 6.3), room_y(-0.3, 4.3);
  int fitted = 0;
  for (const int neighbours : {2, 5, 12}) {
    PointLineFitOptions options;
    options.neighbours = neighbours;
    for (int i = 0; i < 3000; ++i) {
      // Half the queries near a wall, where the k nearest are contested by close ties.
      Eigen::Vector2d query(room_x(rng), room_y(rng));
      if (i % 2 == 0) query.y() = 0.01 * (query.y() - 2.0);
      SurfaceLine expected, line;
      const bool ok = BruteForceLine(map, query, options, expected);
      ASSERT_EQ(ok, FitPointLine(map, query, options, line)) << "query " << i;
      if (!ok) continue;
      ++fitted;
      ASSERT_EQ(expected.normal.x(), line.normal.x()) << "query " << i;
      ASSERT_EQ(expected.normal.y(), line.normal.y()) << "query " << i;
      ASSERT_EQ(expected.offset, line.offset) << "query " << i;
    }
  }
  EXPECT_GT(fitted, 3000);
}

// A beam's end point over the outer iterations of many refinements: small steps (the usual
// case, the pool and the last fit reused), steps past the pool's margin (a new pool), and jumps
// to elsewhere in the room (a new refinement would Reset; here the pool must cope alone).
TEST(BeamLineFits, EveryFitIsBitForBitTheFreshFitAlongRandomWalksOfTheEndPoint) {
  const PointMap map = NoisyRoom();
  const PointLineFitOptions options;
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> room_x(-0.3, 6.3), room_y(-0.3, 4.3);
  std::uniform_real_distribution<double> unit(-1.0, 1.0);
  BeamLineFits fits;
  Eigen::Vector2d query(0.5, 0.02);
  int fitted = 0, refused = 0;
  for (int step = 0; step < 20000; ++step) {
    const int kind = step % 10;
    if (kind == 9) {
      query = Eigen::Vector2d(room_x(rng), room_y(rng));
    } else {
      const double size = kind < 6 ? 0.002 : (kind < 8 ? 0.02 : 0.08);  // 0.08 > the margin
      query += size * Eigen::Vector2d(unit(rng), unit(rng));
    }
    SurfaceLine fresh, reused;
    const bool fresh_ok = FitPointLine(map, query, options, fresh);
    const bool reused_ok = fits.Fit(map, query, options, reused);
    ASSERT_EQ(fresh_ok, reused_ok) << "step " << step;
    if (!fresh_ok) {
      ++refused;
      continue;
    }
    ++fitted;
    ASSERT_EQ(fresh.normal.x(), reused.normal.x()) << "step " << step;
    ASSERT_EQ(fresh.normal.y(), reused.normal.y()) << "step " << step;
    ASSERT_EQ(fresh.offset, reused.offset) << "step " << step;
  }
  // Both outcomes were exercised: lines along the walls, refusals in open space and corners.
  EXPECT_GT(fitted, 2000);
  EXPECT_GT(refused, 500);
}

TEST(BeamLineFits, ResetForgetsTheMapOfTheLastRefinement) {
  const PointMap room = NoisyRoom();
  const PointLineFitOptions options;
  BeamLineFits fits;
  SurfaceLine line;
  const Eigen::Vector2d query(1.0, 0.0);  // on the first wall
  ASSERT_TRUE(fits.Fit(room, query, options, line));
  // The same query on a map with only a vertical wall through it.
  PointMap other;
  std::vector<Eigen::Vector2d> points;
  for (int i = -10; i <= 10; ++i) points.push_back({1.0, 0.03 * i});
  other.Insert(points, std::vector<double>(points.size(), 0.03));
  fits.Reset();
  ASSERT_TRUE(fits.Fit(other, query, options, line));
  EXPECT_NEAR(std::abs(line.normal.x()), 1.0, 1e-12);
  EXPECT_NEAR(line.offset * line.normal.x(), 1.0, 1e-12);
}

}  // namespace
}  // namespace scanloc
