// The SE(2) pose graph: a loop whose dead reckoning drifts is brought back by one closure, a wrong
// closure is held off by the robust loss, and the graph survives g2o's text format.

#include "scanloc/graph/pose_graph.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <random>
#include <stdexcept>
#include <string>
#include <vector>

#include "scanloc/common/parse_error.hpp"
#include "scanloc/io/g2o_file.hpp"

namespace scanloc {
namespace {

namespace fs = std::filesystem;

// A square loop of 4 × 10 one-metre steps, starting at heading 3.0 rad so that yaw crosses ±π.
std::vector<Pose2D> SquareLoop() {
  std::vector<Pose2D> truth = {Pose2D(2.0, -1.0, 3.0)};
  for (int side = 0; side < 4; ++side)
    for (int step = 0; step < 10; ++step) {
      const double turn = step == 9 ? M_PI / 2.0 : 0.0;
      truth.push_back((truth.back() * Pose2D(1.0, 0.0, turn)).Normalized());
    }
  return truth;  // 41 nodes; the last one lies on the first
}

Eigen::Matrix3d Information(double sigma_xy_m, double sigma_yaw_rad) {
  return Eigen::Vector3d(1.0 / (sigma_xy_m * sigma_xy_m), 1.0 / (sigma_xy_m * sigma_xy_m),
                         1.0 / (sigma_yaw_rad * sigma_yaw_rad))
      .asDiagonal();
}

// Dead reckoning over the loop: each step measured with a yaw bias of 0.01 rad and Gaussian noise
// (σ 2 cm, 0.005 rad, seed 7); the nodes start where the odometry puts them.
PoseGraph DriftingLoop(const std::vector<Pose2D>& truth) {
  std::mt19937 random(7);
  std::normal_distribution<double> xy(0.0, 0.02), yaw(0.0, 0.005);
  PoseGraph graph;
  graph.AddNode(truth[0]);
  for (std::size_t i = 1; i < truth.size(); ++i) {
    const Pose2D step = Between(truth[i - 1], truth[i]);
    const Pose2D measured(step.x_m + xy(random), step.y_m + xy(random),
                          step.yaw_rad + 0.01 + yaw(random));
    graph.AddNode(graph.nodes().back() * measured);
    graph.AddEdge({i - 1, i, measured, Information(0.02, 0.01), EdgeKind::kOdometry});
  }
  return graph;
}

double LargestError(const PoseGraph& graph, const std::vector<Pose2D>& truth) {
  double largest = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i)
    largest = std::max(largest, (graph.nodes()[i].Translation() - truth[i].Translation()).norm());
  return largest;
}

PoseGraphEdge TrueClosure(const std::vector<Pose2D>& truth, std::size_t from, std::size_t to) {
  return {from, to, Between(truth[from], truth[to]), Information(0.02, 0.005), EdgeKind::kClosure};
}

TEST(PoseGraph, OneClosureBringsADriftingLoopsEndBackWithinFiveCentimetres) {
  const std::vector<Pose2D> truth = SquareLoop();
  PoseGraph graph = DriftingLoop(truth);
  const double drift_m = (graph.nodes().back().Translation() - truth.back().Translation()).norm();
  EXPECT_GT(drift_m, 2.0);  // dead reckoning ends metres off
  const double dead_reckoning_m = LargestError(graph, truth);
  graph.AddEdge(TrueClosure(truth, 40, 0));
  const PoseGraphSummary summary = graph.Optimise();
  EXPECT_TRUE(summary.converged);
  EXPECT_LT(summary.final_cost, summary.initial_cost);
  // The end comes back onto the start (within the closure's σ). Mid-loop, one closure cannot
  // undo a bias that bent the path: the largest error shrinks fourfold, to under half a metre.
  const Pose2D end = Between(graph.nodes()[0], graph.nodes()[40]);
  EXPECT_LT(std::hypot(end.x_m, end.y_m), 0.05);
  EXPECT_LT(std::abs(NormalizeAngle(end.yaw_rad)), 0.01);
  EXPECT_LT(LargestError(graph, truth), 0.5);
  EXPECT_LT(LargestError(graph, truth), dead_reckoning_m / 4.0);
  EXPECT_EQ(graph.nodes()[0].x_m, truth[0].x_m);  // the gauge did not move
}

TEST(PoseGraph, AWrongClosureIsSetAsideButBendsThePlainLeastSquares) {
  const std::vector<Pose2D> truth = SquareLoop();
  // Node 25 claimed to lie 0.5 m in front of node 5: they are 10 m apart.
  const PoseGraphEdge wrong{5, 25, Pose2D(0.5, 0.0, 0.0), Information(0.02, 0.005),
                            EdgeKind::kClosure};
  PoseGraph right_only = DriftingLoop(truth);
  right_only.AddEdge(TrueClosure(truth, 40, 0));
  right_only.Optimise();
  for (const double loss_scale : {3.0, 0.0}) {
    PoseGraph graph = DriftingLoop(truth);
    graph.AddEdge(TrueClosure(truth, 40, 0));
    graph.AddEdge(wrong);
    PoseGraphOptions options;
    options.closure_loss_scale = loss_scale;
    if (loss_scale == 0.0) options.closure_rejection_chi2 = 0.0;
    const PoseGraphSummary summary = graph.Optimise(options);
    double moved_m = 0.0;
    for (std::size_t i = 0; i < truth.size(); ++i)
      moved_m = std::max(
          moved_m, (graph.nodes()[i].Translation() - right_only.nodes()[i].Translation()).norm());
    if (loss_scale > 0.0) {
      EXPECT_LT(moved_m, 0.01) << "the wrong closure bent the loop";
      EXPECT_EQ(summary.closures_rejected, 1u);
      EXPECT_FALSE(graph.edges().back().active);                    // the wrong one
      EXPECT_TRUE(graph.edges()[graph.edges().size() - 2].active);  // the right one
    } else {
      EXPECT_GT(moved_m, 1.0) << "without the loss the wrong closure should have bent the loop";
    }
  }
}

TEST(PoseGraph, NodesHeldBeforeAClosureStayPutAndOnlyLoopsThroughThemTellTheWholeSolveApart) {
  const std::vector<Pose2D> truth = SquareLoop();
  // A first closure 30 → 20 solved whole, then a second one 40 → 34 solved with the nodes before
  // 34 held: they stay bit for bit, the end comes back as far as the whole solve brings it, and
  // since no loop of the second closure passes through a held node, the two solves agree (within
  // what the first solve's convergence left: tenths of a millimetre).
  PoseGraph graph = DriftingLoop(truth);
  graph.AddEdge(TrueClosure(truth, 30, 20));
  graph.Optimise();
  const std::vector<Pose2D> before = graph.nodes();
  graph.AddEdge(TrueClosure(truth, 40, 34));
  PoseGraph whole = graph;
  const PoseGraphSummary held = graph.Optimise({}, 34);
  whole.Optimise();
  EXPECT_GE(held.iterations, 1);
  for (std::size_t i = 0; i < 34; ++i) {
    EXPECT_EQ(graph.nodes()[i].x_m, before[i].x_m) << i;
    EXPECT_EQ(graph.nodes()[i].yaw_rad, before[i].yaw_rad) << i;
  }
  EXPECT_GT((graph.nodes()[40].Translation() - before[40].Translation()).norm(), 0.05);
  for (std::size_t i = 0; i < truth.size(); ++i)
    EXPECT_LT((graph.nodes()[i].Translation() - whole.nodes()[i].Translation()).norm(), 1e-3) << i;
  // A closure 40 → 25, whose loop runs through the first one's nodes: held from 34 on, the nodes
  // 25–33 cannot take their share and the result departs from the whole solve; a whole solve
  // after it (as LoopCloser::Finish makes) comes back to it.
  PoseGraph loop = DriftingLoop(truth);
  loop.AddEdge(TrueClosure(truth, 30, 20));
  loop.Optimise();
  loop.AddEdge(TrueClosure(truth, 40, 25));
  PoseGraph loop_whole = loop;
  loop.Optimise({}, 34);
  loop_whole.Optimise();
  double apart_m = 0.0;
  for (std::size_t i = 0; i < truth.size(); ++i)
    apart_m = std::max(
        apart_m, (loop.nodes()[i].Translation() - loop_whole.nodes()[i].Translation()).norm());
  std::printf("held from 34: %.4f m from the whole solve\n", apart_m);
  EXPECT_GT(apart_m, 0.01);
  loop.Optimise();
  for (std::size_t i = 0; i < truth.size(); ++i)
    EXPECT_LT((loop.nodes()[i].Translation() - loop_whole.nodes()[i].Translation()).norm(), 1e-3)
        << i;
}

TEST(PoseGraph, SquaredErrorIsTheWhitenedDisagreementOfAnEdge) {
  PoseGraph graph;
  graph.AddNode(Pose2D(0.0, 0.0, M_PI / 2.0));
  graph.AddNode(Pose2D(0.0, 1.0, M_PI / 2.0));
  // Node 1 is 1 m ahead of node 0 in node 0's frame; the edge says 1.1 m, σ 0.1 m: 1σ, χ² = 1.
  const PoseGraphEdge edge{0, 1, Pose2D(1.1, 0.0, 0.0), Information(0.1, 0.1), EdgeKind::kClosure};
  EXPECT_NEAR(graph.SquaredError(edge), 1.0, 1e-9);
}

TEST(PoseGraph, AnEdgesInformationIsReplacedAndAnInactiveEdgeNoLongerPulls) {
  PoseGraph graph;
  graph.AddNode(Pose2D(0.0, 0.0, 0.0));
  graph.AddNode(Pose2D(1.0, 0.0, 0.0));
  graph.AddEdge({0, 1, Pose2D(1.0, 0.0, 0.0), Information(0.01, 0.01), EdgeKind::kSequential});
  graph.AddEdge({0, 1, Pose2D(1.2, 0.0, 0.0), Information(0.01, 0.01), EdgeKind::kOdometry});
  graph.Optimise();
  EXPECT_NEAR(graph.nodes()[1].x_m, 1.1, 1e-4);  // equal weights: halfway (Ceres' tolerance)
  graph.SetInformation(1, Information(0.001, 0.001));
  graph.Optimise();
  EXPECT_NEAR(graph.nodes()[1].x_m, 1.2 - 0.2 / 101.0, 1e-4);  // 100 times the information
  graph.SetInformation(1, Information(0.001, 0.001), false);
  graph.Optimise();
  EXPECT_NEAR(graph.nodes()[1].x_m, 1.0, 1e-4);
  EXPECT_THROW(graph.SetInformation(2, Information(0.01, 0.01)), std::invalid_argument);
  EXPECT_THROW(graph.SetInformation(0, -Information(0.01, 0.01)), std::invalid_argument);
}

TEST(PoseGraph, AnEdgesMeasurementIsReplacedWhenItsNodeMoved) {
  PoseGraph graph;
  graph.AddNode(Pose2D(0.0, 0.0, 0.0));
  graph.AddNode(Pose2D(1.0, 0.0, 0.1));
  graph.AddEdge({0, 1, Pose2D(1.0, 0.0, 0.1), Information(0.01, 0.01), EdgeKind::kSequential});
  graph.SetNode(1, Pose2D(1.0, 0.0, 0.0));
  graph.SetMeasurement(0, Pose2D(1.0, 0.0, 2.0 * M_PI));  // stored normalised
  EXPECT_NEAR(graph.edges()[0].T_from_to.yaw_rad, 0.0, 1e-12);
  graph.Optimise();
  EXPECT_NEAR(graph.nodes()[1].yaw_rad, 0.0, 1e-9);  // nothing pulls it back to 0.1 rad
  EXPECT_THROW(graph.SetMeasurement(1, Pose2D()), std::invalid_argument);
  EXPECT_THROW(graph.SetMeasurement(0, Pose2D(NAN, 0.0, 0.0)), std::invalid_argument);
}

TEST(PoseGraph, InvalidEdgesAndNodesAreRefusedNamingTheProblem) {
  PoseGraph graph;
  graph.AddNode(Pose2D());
  graph.AddNode(Pose2D(1.0, 0.0, 0.0));
  EXPECT_THROW(graph.AddNode(Pose2D(NAN, 0.0, 0.0)), std::invalid_argument);
  EXPECT_THROW(graph.AddEdge({0, 2, Pose2D(), Eigen::Matrix3d::Identity()}), std::invalid_argument);
  EXPECT_THROW(graph.AddEdge({1, 1, Pose2D(), Eigen::Matrix3d::Identity()}), std::invalid_argument);
  Eigen::Matrix3d indefinite = Eigen::Matrix3d::Identity();
  indefinite(2, 2) = -1.0;
  try {
    graph.AddEdge({0, 1, Pose2D(), indefinite});
    ADD_FAILURE() << "an indefinite information was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_NE(std::string(error.what()).find("positive definite"), std::string::npos);
  }
  EXPECT_TRUE(graph.edges().empty());
  PoseGraphOptions options;
  options.fixed_node = 5;
  EXPECT_THROW(graph.Optimise(options), std::invalid_argument);
}

class G2oFileTest : public ::testing::Test {
 protected:
  void SetUp() override {
    directory_ = fs::temp_directory_path() /
                 ("scanloc_g2o_" +
                  std::string(::testing::UnitTest::GetInstance()->current_test_info()->name()));
    fs::create_directories(directory_);
  }
  void TearDown() override { fs::remove_all(directory_); }
  std::string Write(const std::string& name, const std::string& text) const {
    const std::string path = (directory_ / name).string();
    std::ofstream(path) << text;
    return path;
  }
  fs::path directory_;
};

TEST_F(G2oFileTest, AGraphReadsBackExactlyWithClosuresKnownByTheirGap) {
  const std::vector<Pose2D> truth = SquareLoop();
  PoseGraph graph = DriftingLoop(truth);
  PoseGraphEdge closure = TrueClosure(truth, 40, 0);
  closure.information(0, 1) = closure.information(1, 0) = 3.0;  // off-diagonal terms survive
  graph.AddEdge(closure);
  const std::string path = (directory_ / "loop.g2o").string();
  WriteG2o(graph, path);
  const PoseGraph read = ReadG2o(path);
  ASSERT_EQ(read.nodes().size(), graph.nodes().size());
  ASSERT_EQ(read.edges().size(), graph.edges().size());
  for (std::size_t i = 0; i < graph.nodes().size(); ++i) {
    EXPECT_EQ(read.nodes()[i].x_m, graph.nodes()[i].x_m);
    EXPECT_EQ(read.nodes()[i].yaw_rad, graph.nodes()[i].yaw_rad);
  }
  for (std::size_t i = 0; i < graph.edges().size(); ++i) {
    EXPECT_EQ(read.edges()[i].T_from_to.y_m, graph.edges()[i].T_from_to.y_m);
    EXPECT_EQ(read.edges()[i].information, graph.edges()[i].information);
  }
  EXPECT_EQ(read.edges()[0].kind, EdgeKind::kSequential);
  EXPECT_EQ(read.edges().back().kind, EdgeKind::kClosure);
  std::ifstream in(path);
  const std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  EXPECT_NE(text.find("\nFIX 0\n"), std::string::npos);
}

TEST_F(G2oFileTest, ClosuresTheGraphSetAsideAreNotWritten) {
  const std::vector<Pose2D> truth = SquareLoop();
  PoseGraph graph = DriftingLoop(truth);
  graph.AddEdge(TrueClosure(truth, 40, 0));
  // Node 25 claimed to lie 0.5 m in front of node 5: they are 10 m apart.
  graph.AddEdge({5, 25, Pose2D(0.5, 0.0, 0.0), Information(0.02, 0.005), EdgeKind::kClosure});
  graph.Optimise();
  ASSERT_FALSE(graph.edges().back().active);  // the wrong closure was set aside
  const std::string path = (directory_ / "loop.g2o").string();
  WriteG2o(graph, path);
  const PoseGraph read = ReadG2o(path);
  ASSERT_EQ(read.edges().size(), graph.edges().size() - 1);
  EXPECT_EQ(read.edges().back().from, 40u);  // the true closure 40 -> 0 stays
  EXPECT_EQ(read.edges().back().to, 0u);
}

TEST_F(G2oFileTest, MalformedGraphsAreRefusedWithTheirLine) {
  const std::string vertices = "VERTEX_SE2 0 0 0 0\nVERTEX_SE2 1 1 0 0\n";
  const std::vector<std::pair<std::string, std::size_t>> cases = {
      {"VERTEX_SE2 1 0 0 0\n", 1},                           // ids out of order
      {vertices + "EDGE_SE2 0 2 1 0 0 1 0 0 1 0 1\n", 3},    // unknown vertex
      {vertices + "EDGE_SE2 0 1 1 0 0 1 0 0 1 0 -1\n", 3},   // not definite
      {vertices + "EDGE_SE2 0 1 1 0 0 1 0 0 1 0\n", 3},      // an entry short
      {vertices + "EDGE_SE2 0 1 1 0 nan 1 0 0 1 0 1\n", 3},  // not finite
      {vertices + "POINT 3 4\n", 3},                         // not g2o
  };
  for (std::size_t i = 0; i < cases.size(); ++i) {
    const std::string path = Write("bad-" + std::to_string(i) + ".g2o", cases[i].first);
    try {
      ReadG2o(path);
      ADD_FAILURE() << cases[i].first << " was read";
    } catch (const ParseError& error) {
      EXPECT_EQ(error.file(), path);
      EXPECT_EQ(error.line(), cases[i].second) << error.what();
    }
  }
  EXPECT_THROW(ReadG2o((directory_ / "missing.g2o").string()), std::runtime_error);
}

}  // namespace
}  // namespace scanloc
