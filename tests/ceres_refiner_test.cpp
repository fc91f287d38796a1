#include "scanloc/refinement/ceres_refiner.hpp"

#include <gtest/gtest.h>

#include <limits>
#include <random>

#include "scanloc/maps/line_map.hpp"
#include "scanloc/maps/point_map.hpp"
#include "scanloc/worlds/laser_simulator.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

using testing::Classroom;

LaserScan Observe(const LineMap& world, const Pose2D& pose, double noise_m, unsigned seed) {
  LaserSimulatorOptions laser;
  laser.beam_count = 720;
  laser.range_noise_m = noise_m;
  laser.range_noise_per_m = 0.0;
  std::mt19937 rng(seed);
  return SimulateLaser(world, pose, laser, rng);
}

std::string Describe(const RefinementResult& r) {
  return "pose " + std::to_string(r.T_world_laser.x_m) + " " + std::to_string(r.T_world_laser.y_m) +
         " " + std::to_string(r.T_world_laser.yaw_rad) + ", iterations " +
         std::to_string(r.iterations) + ", converged " + std::to_string(r.converged) +
         ", EV before/after " + std::to_string(r.test_before.expect_value_m) + "/" +
         std::to_string(r.test_after.expect_value_m);
}

// Offsets up to 0.3 m and 0.1 rad, drawn with a fixed seed.
std::vector<Pose2D> Offsets(unsigned seed, int count) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> t(-0.3, 0.3), r(-0.1, 0.1);
  std::vector<Pose2D> offsets;
  for (int i = 0; i < count; ++i) offsets.push_back({t(rng), t(rng), r(rng)});
  offsets.push_back({0.3, -0.3, 0.1});
  return offsets;
}

TEST(RefineCeres, RecoversTruePostureFromOffsetsWithin5mmAnd2mradNoiseFree) {
  const LineMap map = Classroom();
  const Pose2D truth{2.2, 3.1, 0.4};
  const LaserScan scan = Observe(map, truth, 0.0, 1);
  for (const Pose2D& offset : Offsets(11, 12)) {
    const Pose2D start = truth * offset;
    const RefinementResult r = RefineCeres(MapView{&map, nullptr}, scan, start, ScoringOptions{});
    const Pose2D error = Between(truth, r.T_world_laser);
    EXPECT_LT(std::hypot(error.x_m, error.y_m), 0.005) << Describe(r);
    EXPECT_LT(std::abs(error.yaw_rad), 0.002) << Describe(r);
    EXPECT_TRUE(r.converged) << Describe(r);
    EXPECT_LE(r.test_after.expect_value_m, r.test_before.expect_value_m) << Describe(r);
    EXPECT_FALSE(r.degenerate) << r.degeneracy;
  }
}

TEST(RefineCeres, RecoversTruePostureWithinTheNoiseLevelWith2cmRangeNoise) {
  const LineMap map = Classroom();
  const Pose2D truth{4.1, 2.0, -2.0};
  for (unsigned seed = 1; seed <= 3; ++seed) {
    const LaserScan scan = Observe(map, truth, 0.02, seed);
    for (const Pose2D& offset : Offsets(100 + seed, 4)) {
      const RefinementResult r =
          RefineCeres(MapView{&map, nullptr}, scan, truth * offset, ScoringOptions{});
      const Pose2D error = Between(truth, r.T_world_laser);
      EXPECT_LT(std::hypot(error.x_m, error.y_m), 0.02) << Describe(r);
      EXPECT_LT(std::abs(error.yaw_rad), 0.005) << Describe(r);
      EXPECT_LE(r.test_after.expect_value_m, r.test_before.expect_value_m) << Describe(r);
      ASSERT_TRUE(r.has_covariance);
      // The estimated standard deviation is of the order of the actual error (2 cm noise, 720
      // beams: a few millimetres).
      EXPECT_LT(std::sqrt(r.covariance(0, 0)), 0.01);
      EXPECT_GT(std::sqrt(r.covariance(0, 0)), 1e-4);
    }
  }
}

TEST(RefineCeres, ThirtyPercentOfBeamsOnClutterDoNotPullThePostureOff) {
  const LineMap map = Classroom();
  LineMap world = map;
  // Boxes and people near the laser that are not in the map, shadowing ~30 % of the beams.
  world.segments.push_back({{2.9, 2.4}, {3.5, 2.4}});
  world.segments.push_back({{3.5, 2.4}, {3.5, 3.0}});
  world.segments.push_back({{1.6, 3.4}, {1.6, 4.3}});
  world.segments.push_back({{2.0, 4.6}, {2.8, 4.6}});
  const Pose2D truth{2.4, 3.3, 0.2};
  const LaserScan scan = Observe(world, truth, 0.01, 5);
  const SimulatedScan clean = SimulateFromLines(map, scan.layout, truth);
  int cluttered = 0;
  for (std::size_t k = 0; k < scan.size(); ++k)
    cluttered += scan.IsValid(k) && std::abs(scan.ranges_m[k] - clean.ranges_m[k]) > 0.1;
  ASSERT_GT(cluttered, 0.28 * scan.size()) << "the clutter must hide about 30 % of the beams";
  for (const Pose2D& offset : Offsets(21, 6)) {
    const RefinementResult r =
        RefineCeres(MapView{&map, nullptr}, scan, truth * offset, ScoringOptions{});
    const Pose2D error = Between(truth, r.T_world_laser);
    EXPECT_LT(std::hypot(error.x_m, error.y_m), 0.01) << Describe(r);
    EXPECT_LT(std::abs(error.yaw_rad), 0.003) << Describe(r);
  }
}

TEST(RefineCeres, WorksOnAPointMapSampledFromTheLines) {
  const LineMap lines = Classroom();
  const PointMap points = PointMapFromLines(lines, 0.0075);
  const Pose2D truth{3.0, 4.0, 1.0};
  const LaserScan scan = Observe(lines, truth, 0.0, 3);
  for (const Pose2D& offset : Offsets(31, 6)) {
    const RefinementResult r =
        RefineCeres(MapView{nullptr, &points}, scan, truth * offset, ScoringOptions{});
    const Pose2D error = Between(truth, r.T_world_laser);
    // The map's points are 5 cm apart after de-duplication: the local lines carry that.
    EXPECT_LT(std::hypot(error.x_m, error.y_m), 0.01) << Describe(r);
    EXPECT_LT(std::abs(error.yaw_rad), 0.003) << Describe(r);
  }
}

TEST(RefineCeres, LongCorridorIsFlaggedDegenerateAlongItsAxis) {
  LineMap corridor;
  corridor.segments = {{{-100.0, -1.0}, {100.0, -1.0}}, {{-100.0, 1.0}, {100.0, 1.0}}};
  const Pose2D truth{0.0, 0.2, 0.05};
  const LaserScan scan = Observe(corridor, truth, 0.01, 9);
  const RefinementResult r =
      RefineCeres(MapView{&corridor, nullptr}, scan, {0.1, 0.25, 0.0}, ScoringOptions{});
  EXPECT_TRUE(r.degenerate);
  EXPECT_NE(r.degeneracy.find("translation along (1.00, 0.00)"), std::string::npos) << r.degeneracy;
  // Across the corridor and in heading the posture is still recovered.
  EXPECT_NEAR(r.T_world_laser.y_m, 0.2, 0.01);
  EXPECT_NEAR(r.T_world_laser.yaw_rad, 0.05, 0.005);
}

// The corridor of the test above leaves its axis to chance; a prior (the odometry's prediction)
// holds the posture there, while across the corridor the beams outweigh the prior's 10 cm error.
TEST(RefineCeres, APriorHoldsTheCorridorAxisTheBeamsLeaveFree) {
  LineMap corridor;
  corridor.segments = {{{-100.0, -1.0}, {100.0, -1.0}}, {{-100.0, 1.0}, {100.0, 1.0}}};
  const Pose2D truth{0.0, 0.2, 0.05};
  const LaserScan scan = Observe(corridor, truth, 0.01, 9);
  CeresRefinerOptions options;
  options.prior = PosturePrior{{0.0, 0.3, 0.0}, {1.0 / 0.05, 1.0 / 0.05, 0.0}};
  const RefinementResult r =
      RefineCeres(MapView{&corridor, nullptr}, scan, {0.3, 0.25, 0.0}, ScoringOptions{}, options);
  EXPECT_NEAR(r.T_world_laser.x_m, 0.0, 0.005) << Describe(r);
  EXPECT_NEAR(r.T_world_laser.y_m, 0.2, 0.01) << Describe(r);
  EXPECT_NEAR(r.T_world_laser.yaw_rad, 0.05, 0.005) << Describe(r);
  // The uncertainty is the beams' alone: the axis is still reported free.
  EXPECT_TRUE(r.degenerate);
  EXPECT_NE(r.degeneracy.find("translation along (1.00, 0.00)"), std::string::npos) << r.degeneracy;
}

// Where the scan pins the posture, a prior 0.2 m off (σ 5 cm) moves it by millimetres.
TEST(RefineCeres, APriorBarelyMovesAPostureTheScanPins) {
  const LineMap map = Classroom();
  const Pose2D truth{2.2, 3.1, 0.4};
  const LaserScan scan = Observe(map, truth, 0.0, 1);
  CeresRefinerOptions options;
  options.prior = PosturePrior{truth * Pose2D{0.2, -0.2, 0.0}, {20.0, 20.0, 0.0}};
  for (const Pose2D& offset : Offsets(11, 4)) {
    const RefinementResult r =
        RefineCeres(MapView{&map, nullptr}, scan, truth * offset, ScoringOptions{}, options);
    const Pose2D error = Between(truth, r.T_world_laser);
    EXPECT_LT(std::hypot(error.x_m, error.y_m), 0.005) << Describe(r);
    EXPECT_LT(std::abs(error.yaw_rad), 0.002) << Describe(r);
  }
}

// A prior of zero weight adds nothing: the posture of no prior, to the last bits that matter.
TEST(RefineCeres, APriorOfZeroWeightGivesThePostureOfNone) {
  const LineMap map = Classroom();
  const Pose2D truth{2.2, 3.1, 0.4};
  const LaserScan scan = Observe(map, truth, 0.02, 5);
  CeresRefinerOptions zero;
  zero.prior = PosturePrior{truth * Pose2D{0.3, 0.3, 0.1}, Eigen::Vector3d::Zero()};
  for (const Pose2D& offset : Offsets(21, 4)) {
    const Pose2D start = truth * offset;
    const RefinementResult none =
        RefineCeres(MapView{&map, nullptr}, scan, start, ScoringOptions{});
    const RefinementResult with =
        RefineCeres(MapView{&map, nullptr}, scan, start, ScoringOptions{}, zero);
    EXPECT_NEAR(with.T_world_laser.x_m, none.T_world_laser.x_m, 1e-12);
    EXPECT_NEAR(with.T_world_laser.y_m, none.T_world_laser.y_m, 1e-12);
    EXPECT_NEAR(with.T_world_laser.yaw_rad, none.T_world_laser.yaw_rad, 1e-12);
    EXPECT_EQ(with.iterations, none.iterations);
  }
}

TEST(RefineCeres, MirrorCandidateStaysAtTheMirrorAndScoresWorse) {
  const LineMap map = Classroom();
  const Pose2D truth{1.126, 3.112, 0.0463};
  const LaserScan scan = Observe(map, truth, 0.02, 4);
  // The posture symmetric about the room's centre, 5 cm and 0.02 rad off.
  const Pose2D mirror{6.3 - 1.126 + 0.05, 7.0 - 3.112 - 0.03, NormalizeAngle(0.0463 + M_PI + 0.02)};
  const RefinementResult right =
      RefineCeres(MapView{&map, nullptr}, scan, truth * Pose2D{0.05, 0.0, 0.01}, ScoringOptions{});
  const RefinementResult wrong =
      RefineCeres(MapView{&map, nullptr}, scan, mirror, ScoringOptions{});
  EXPECT_GT(std::hypot(wrong.T_world_laser.x_m - truth.x_m, wrong.T_world_laser.y_m - truth.y_m),
            3.0)
      << "the mirror candidate must not jump to the true posture";
  EXPECT_LT(wrong.test_after.match_pairs, right.test_after.match_pairs);
  EXPECT_GT(wrong.test_after.expect_value_m, right.test_after.expect_value_m);
}

TEST(RefineCeres, EmptyMapAndAllInvalidScanAreReportedNotCrashed) {
  const LineMap empty;
  const LineMap map = Classroom();
  const LaserScan scan = Observe(map, {2.0, 2.0, 0.0}, 0.0, 1);
  const RefinementResult on_empty =
      RefineCeres(MapView{&empty, nullptr}, scan, {2.0, 2.0, 0.0}, ScoringOptions{});
  EXPECT_FALSE(on_empty.converged);
  EXPECT_TRUE(on_empty.degenerate);
  EXPECT_EQ(on_empty.test_after.valid_pairs, 0);
  LaserScan blind = scan;
  std::fill(blind.ranges_m.begin(), blind.ranges_m.end(), -1.0);
  const RefinementResult on_blind =
      RefineCeres(MapView{&map, nullptr}, blind, {2.0, 2.0, 0.0}, ScoringOptions{});
  EXPECT_FALSE(on_blind.converged);
  EXPECT_TRUE(on_blind.degenerate);
}

TEST(RefineCeres, WithoutInitialScoringOnAPointMapGivesTheSamePosture) {
  const LineMap lines = Classroom();
  const PointMap points = PointMapFromLines(lines, 0.0075);
  const Pose2D truth{3.0, 4.0, 1.0};
  const LaserScan scan = Observe(lines, truth, 0.01, 8);
  CeresRefinerOptions quiet;
  quiet.score_initial = false;
  const Pose2D start = truth * Pose2D{0.1, -0.1, 0.05};
  const RefinementResult a = RefineCeres(MapView{nullptr, &points}, scan, start, {}, quiet);
  const RefinementResult b = RefineCeres(MapView{nullptr, &points}, scan, start, {});
  EXPECT_EQ(a.test_before.valid_pairs, 0);  // not scored
  EXPECT_GT(b.test_before.valid_pairs, 0);
  EXPECT_DOUBLE_EQ(a.T_world_laser.x_m, b.T_world_laser.x_m);
  EXPECT_DOUBLE_EQ(a.T_world_laser.yaw_rad, b.T_world_laser.yaw_rad);
}

// The classroom with 40 short segments of clutter, seen by a 181-beam laser with 3 cm noise,
// mapped from six scans laid 3 cm and a few mrad off: a map on which an outer iteration can
// pair a beam with a different neighbourhood each time round (seeds fixed).
struct ClutteredScene {
  LineMap lines = Classroom();
  PointMap points;
  LaserScan scan;
  Pose2D truth{3.2, 3.7, 0.6};

  ClutteredScene() {
    std::mt19937 clutter(5);
    std::uniform_real_distribution<double> x(0.3, 6.0), y(0.3, 6.7), a(0.0, 6.28), l(0.05, 0.4);
    for (int i = 0; i < 40; ++i) {
      const Eigen::Vector2d p(x(clutter), y(clutter));
      const double t = a(clutter), length = l(clutter);
      lines.segments.push_back({p, p + length * Eigen::Vector2d(std::cos(t), std::sin(t))});
    }
    LaserSimulatorOptions laser;
    laser.beam_count = 181;
    laser.range_noise_m = 0.03;
    laser.range_noise_per_m = 0.0;
    std::mt19937 rng(15);
    std::normal_distribution<double> slip(0.0, 0.03);
    for (int m = 0; m < 6; ++m) {
      const Pose2D at{2.0 + 0.5 * m, 3.0 + 0.3 * m, 0.5 * m};
      const Pose2D off{slip(rng), slip(rng), 0.3 * slip(rng)};
      points.InsertScan(SimulateLaser(lines, at * off, laser, rng), at);
    }
    scan = SimulateLaser(lines, truth, laser, rng);
  }
};

// Outer iterations that come back to a posture they started from cycle; the refinement stops
// there and returns what running them to the cap returns. Checked against the runs with a cap
// one period lower, which end where the cap leaves them: the same posture and covariance, to
// the bit. The scene's refinement from 0.3 m and 0.1 rad off cycles (a period of 4 today).
TEST(RefineCeres, CyclingOuterIterationsEndWhereTheCapWouldLeaveThem) {
  const ClutteredScene scene;
  const Pose2D start = scene.truth * Pose2D{0.3, -0.3, 0.1};
  std::vector<RefinementResult> by_cap(16);
  for (int cap = 1; cap <= 15; ++cap) {
    CeresRefinerOptions options;
    options.max_outer_iterations = cap;
    by_cap[cap] =
        RefineCeres(MapView{nullptr, &scene.points}, scene.scan, start, ScoringOptions{}, options);
  }
  const int period = by_cap[15].cycle_period;
  ASSERT_GT(period, 1) << Describe(by_cap[15]);
  // The first cap whose run found the cycle: its iterations started from `first` postures, of
  // which the last `period` cycle.
  int found = 15;
  while (found > 1 && by_cap[found - 1].cycle_period > 0) --found;
  ASSERT_GT(found - period, 1) << "the cycle was found too early to compare with runs to the cap";
  for (int cap = found; cap <= 15; ++cap) {
    const RefinementResult& shortcut = by_cap[cap];
    const RefinementResult& run = by_cap[cap - period];
    EXPECT_EQ(shortcut.cycle_period, period);
    EXPECT_EQ(shortcut.iterations, cap);
    EXPECT_FALSE(shortcut.converged);
    EXPECT_EQ(shortcut.T_world_laser.x_m, run.T_world_laser.x_m) << "cap " << cap;
    EXPECT_EQ(shortcut.T_world_laser.y_m, run.T_world_laser.y_m) << "cap " << cap;
    EXPECT_EQ(shortcut.T_world_laser.yaw_rad, run.T_world_laser.yaw_rad) << "cap " << cap;
    EXPECT_TRUE(shortcut.covariance == run.covariance) << "cap " << cap;
    EXPECT_EQ(shortcut.test_after.expect_value_m, run.test_after.expect_value_m) << "cap " << cap;
  }
}

TEST(CeresRefinerOptions, APriorWithANegativeOrNonFiniteWeightIsRefused) {
  CeresRefinerOptions options;
  options.prior = PosturePrior{{}, {1.0, -1.0, 0.0}};
  EXPECT_THROW(options.Validate(), std::invalid_argument);
  options.prior->inverse_sigma = {1.0, std::numeric_limits<double>::infinity(), 0.0};
  EXPECT_THROW(options.Validate(), std::invalid_argument);
  options.prior->inverse_sigma = {1.0, 1.0, 0.0};
  EXPECT_NO_THROW(options.Validate());
}

TEST(CeresRefinerOptions, AbsurdValuesAreRefused) {
  CeresRefinerOptions options;
  options.max_outer_iterations = 0;
  EXPECT_THROW(options.Validate(), std::invalid_argument);
  options = {};
  options.max_incidence_rad = 2.0;
  EXPECT_THROW(options.Validate(), std::invalid_argument);
  EXPECT_THROW(ParseIncidenceWeighting("sine"), std::invalid_argument);
}

}  // namespace
}  // namespace scanloc
