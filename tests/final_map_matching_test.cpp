// The final map matching over a synthetic ring building: nodes displaced from the map they laid
// are pulled back onto it, a tight chain holds where the matches disagree by their noise, one
// node is matched per spacing of path, and a node turned away from both its neighbours is matched
// from where their odometry puts it (loop_closure.final_match_neighbour_sigmas).

#include "scanloc/session/final_map_matching.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

#include "scanloc/maps/point_map.hpp"
#include "scanloc/session/loop_closure.hpp"
#include "scanloc/worlds/laser_simulator.hpp"
#include "scanloc/worlds/robot_path.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

struct Ring {
  std::vector<Pose2D> truth;
  std::vector<LaserScan> scans;
  PointMap map{PointMapOptions{}};  // every scan laid at its true posture
};

// One lap and a half around the ring, every 0.4 m, with a 180-beam laser of 12 m range (seed 21).
Ring DriveRing() {
  const LineMap world = testing::RingBuilding();
  RobotPathOptions path;
  path.step_m = 0.4;
  const std::vector<Eigen::Vector2d> corners = {{22, 2}, {22, 14}, {2, 14},
                                                {2, 2},  {22, 2},  {22, 10}};
  Ring ring;
  ring.truth = FollowWaypoints(Pose2D(2.0, 2.0, 0.0), corners, path);
  std::mt19937 random(21);
  for (const Pose2D& pose : ring.truth) {
    ring.scans.push_back(SimulateLaser(world, pose, testing::RingBuildingLaser(), random));
    ring.map.InsertScan(ring.scans.back(), pose);
  }
  return ring;
}

// A graph whose nodes lie at `postures`, joined by their own relative postures with σ of
// sigma_m and sigma_rad: a chain that agrees with itself wherever it lies.
PoseGraph Chain(const std::vector<Pose2D>& postures, double sigma_m, double sigma_rad) {
  PoseGraph graph;
  for (const Pose2D& p : postures) graph.AddNode(p);
  const Eigen::Matrix3d information =
      Eigen::Vector3d(1.0 / (sigma_m * sigma_m), 1.0 / (sigma_m * sigma_m),
                      1.0 / (sigma_rad * sigma_rad))
          .asDiagonal();
  for (std::size_t i = 1; i < postures.size(); ++i)
    graph.AddEdge(
        {i - 1, i, Between(postures[i - 1], postures[i]), information, EdgeKind::kSequential});
  return graph;
}

std::vector<NodeScan> Scans(const Ring& ring) {
  std::vector<NodeScan> nodes;
  for (std::size_t i = 0; i < ring.scans.size(); ++i)
    nodes.push_back({i, &ring.scans[i], 0.4 * static_cast<double>(i)});
  return nodes;
}

double MeanError(const PoseGraph& graph, const std::vector<Pose2D>& truth) {
  double sum = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i)
    sum += (graph.nodes()[i].Translation() - truth[i].Translation()).norm();
  return sum / static_cast<double>(truth.size());
}

FinalMatchSummary Match(const Ring& ring, const FinalMatchOptions& options, PoseGraph& graph) {
  return MatchNodesOnFinalMap({nullptr, &ring.map}, Scans(ring), LaserMounting{},
                              LocalisationOptions{}, options, 0.005, 0.001, PoseGraphOptions{},
                              graph);
}

TEST(FinalMapMatching, NodesDisplacedFromTheMapTheyLaidArePulledBackOntoIt) {
  const Ring ring = DriveRing();
  // A chain bent off the map by a heading error that grows and shrinks along the path (±15 mrad)
  // and 6 cm sideways at most: the postures a drifting matched chain leaves after its solve.
  std::vector<Pose2D> bent;
  for (std::size_t i = 0; i < ring.truth.size(); ++i) {
    const double phase = 0.05 * static_cast<double>(i);
    bent.push_back(ring.truth[i] * Pose2D(0.0, 0.06 * std::sin(phase), 0.015 * std::cos(phase)));
  }
  PoseGraph graph = Chain(bent, 0.02, 0.005);
  const double before = MeanError(graph, ring.truth);
  FinalMatchOptions options;
  options.spacing_m = 0.0;
  const FinalMatchSummary summary = Match(ring, options, graph);
  std::printf("mean node error %.4f m before, %.4f m after; %zu of %zu matches joined\n", before,
              MeanError(graph, ring.truth), summary.joined, summary.matched);
  EXPECT_EQ(summary.matched, ring.truth.size());
  EXPECT_GT(summary.joined, ring.truth.size() * 9 / 10);
  EXPECT_GT(before, 0.03);
  EXPECT_LT(MeanError(graph, ring.truth), 0.01);
  EXPECT_GT(summary.largest_shift_m, 0.04);
  EXPECT_GE(summary.solve_iterations, 1);
  EXPECT_EQ(graph.edges().size(), ring.truth.size() - 1);  // the matches are not kept as edges
}

TEST(FinalMapMatching, ATightChainHoldsWhereTheMatchesDisagreeByTheirNoise) {
  const Ring ring = DriveRing();
  // The map laid at the true postures, the nodes there too, joined by a perfect odometry (σ
  // 0.1 mm, 0.01 mrad): matches that scatter by the scans' own noise barely move them.
  // A chain of a matching's own σ (2 cm, 5 mrad) follows them further.
  PoseGraph tight = Chain(ring.truth, 1e-4, 1e-5), loose = Chain(ring.truth, 0.02, 0.005);
  FinalMatchOptions options;
  options.spacing_m = 0.0;
  const FinalMatchSummary summary = Match(ring, options, tight);
  Match(ring, options, loose);
  std::printf("mean node error %.5f m on the tight chain, %.5f m on the loose one\n",
              MeanError(tight, ring.truth), MeanError(loose, ring.truth));
  EXPECT_GT(summary.joined, ring.truth.size() * 9 / 10);
  EXPECT_LT(MeanError(tight, ring.truth), 0.002);  // 1.5 mm: the whole chain moved as one
  EXPECT_GT(MeanError(loose, ring.truth), 2.0 * MeanError(tight, ring.truth));  // 3.7 mm
}

TEST(FinalMapMatching, OneNodeIsMatchedPerSpacingOfPath) {
  const Ring ring = DriveRing();
  PoseGraph graph = Chain(ring.truth, 0.02, 0.005);
  FinalMatchOptions options;
  options.spacing_m = 1.0;  // nodes every 0.4 m: the 1st, 4th, 7th, ... (path 0, 1.2, 2.4 m)
  const FinalMatchSummary summary = Match(ring, options, graph);
  EXPECT_EQ(summary.matched, (ring.truth.size() + 2) / 3);
}

TEST(FinalMapMatching, OnAnEmptyMapNothingJoinsAndTheNodesStay) {
  const Ring ring = DriveRing();
  PoseGraph graph = Chain(ring.truth, 0.02, 0.005);
  const PointMap empty{PointMapOptions{}};
  const FinalMatchSummary summary =
      MatchNodesOnFinalMap({nullptr, &empty}, Scans(ring), LaserMounting{}, LocalisationOptions{},
                           FinalMatchOptions{}, 0.005, 0.001, PoseGraphOptions{}, graph);
  EXPECT_EQ(summary.joined, 0u);
  EXPECT_EQ(summary.solve_iterations, 0);
  EXPECT_DOUBLE_EQ(summary.largest_shift_m, 0.0);
  EXPECT_DOUBLE_EQ(MeanError(graph, ring.truth), 0.0);
}

TEST(FinalMapMatching, ANegativeSpacingIsRefused) {
  FinalMatchOptions options;
  options.spacing_m = -0.1;
  EXPECT_THROW(options.Validate(), std::invalid_argument);
}

// A session's nodes on the ring, their odometry the truth, all laid where they truly are but node
// `k`, laid turned by `turn_rad` (its match settled on another heading): the chain's edges hold the
// turn, its neighbours' odometry does not.
LoopCloser NodesWithOneTurned(const Ring& ring, std::size_t k, double turn_rad,
                              double neighbour_sigmas) {
  LoopClosureOptions options;
  options.final_match.spacing_m = 0.0;
  options.final_match.neighbour_sigmas = neighbour_sigmas;
  LoopCloser closer(options, LaserMounting{});
  for (std::size_t i = 0; i < ring.truth.size(); ++i) {
    const Pose2D laid = i == k ? ring.truth[i] * Pose2D(0.0, 0.0, turn_rad) : ring.truth[i];
    closer.AddNode(i, ring.scans[i], laid,
                   Eigen::Matrix3d(Eigen::Vector3d(4e-4, 4e-4, 2.5e-5).asDiagonal()),
                   ring.truth[i]);
  }
  return closer;
}

TEST(FinalMapMatching, ANodeTurnedAwayFromBothNeighboursIsMatchedFromWhereTheyPutIt) {
  const Ring ring = DriveRing();
  const std::size_t k = 20;
  const double turn_rad = 0.5;
  LoopCloser with = NodesWithOneTurned(ring, k, turn_rad, 3.0);
  LoopCloser without = NodesWithOneTurned(ring, k, turn_rad, 0.0);
  const FinalMatchSummary summary =
      with.MatchOnFinalMap({nullptr, &ring.map}, LocalisationOptions{});
  without.MatchOnFinalMap({nullptr, &ring.map}, LocalisationOptions{});
  const double error_with =
      std::abs(NormalizeAngle(with.graph().nodes()[k].yaw_rad - ring.truth[k].yaw_rad));
  const double error_without =
      std::abs(NormalizeAngle(without.graph().nodes()[k].yaw_rad - ring.truth[k].yaw_rad));
  std::printf("node %zu heading error %.4f rad from its neighbours' postures too, %.4f without\n",
              k, error_with, error_without);
  EXPECT_EQ(summary.from_neighbours, 1u);  // the only node that stands out
  EXPECT_EQ(summary.took_neighbours, 1u);
  EXPECT_GT(error_without, 0.45);  // its own match cannot turn it back
  EXPECT_LT(error_with, 0.5 * error_without);
}

TEST(FinalMapMatching, ANegativeNeighbourSigmasIsRefused) {
  FinalMatchOptions options;
  options.neighbour_sigmas = -1.0;
  EXPECT_THROW(options.Validate(), std::invalid_argument);
}

}  // namespace
}  // namespace scanloc
