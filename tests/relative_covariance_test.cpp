// The covariance of one node's posture relative to another, compounded along the pose graph: the
// first-order formulas on a straight chain, consistency between the two directions, and a closure
// that shortens the path.

#include "scanloc/graph/relative_covariance.hpp"

#include <gtest/gtest.h>
#include <Eigen/LU>

#include <cmath>
#include <stdexcept>

namespace scanloc {
namespace {

Eigen::Matrix3d Diagonal(double a, double b, double c) {
  return Eigen::Vector3d(a, b, c).asDiagonal();
}

// The Jacobian of a posture's inverse at T (written out here, apart from the library's).
Eigen::Matrix3d InverseJacobian(const Pose2D& T) {
  const double c = std::cos(T.yaw_rad), s = std::sin(T.yaw_rad);
  Eigen::Matrix3d jacobian;
  jacobian << -c, -s, s * T.x_m - c * T.y_m, s, -c, c * T.x_m + s * T.y_m, 0, 0, -1;
  return jacobian;
}

// Nodes one metre apart along x, each edge with covariance diag(a, b, c).
PoseGraph StraightChain(std::size_t nodes, const Eigen::Matrix3d& covariance) {
  PoseGraph graph;
  graph.AddNode(Pose2D(0.0, 0.0, 0.0));
  for (std::size_t i = 1; i < nodes; ++i) {
    graph.AddNode(Pose2D(static_cast<double>(i), 0.0, 0.0));
    graph.AddEdge({i - 1, i, Pose2D(1.0, 0.0, 0.0), covariance.inverse(), EdgeKind::kSequential});
  }
  return graph;
}

TEST(RelativeCovariance, TwoStepsAlongXCarryTheFirstHeadingErrorIntoTheLateralVariance) {
  const double a = 1e-4, b = 4e-4, c = 1e-3;
  const PoseGraph graph = StraightChain(3, Diagonal(a, b, c));
  const Eigen::Matrix3d covariance = *RelativeCovariance(graph, 0, 2);
  // Σ₂ = J Σ₁ Jᵀ + Σ with J moving the first step's heading error over the second metre.
  Eigen::Matrix3d expected;
  expected << 2 * a, 0, 0, 0, 2 * b + c, c, 0, c, 2 * c;
  EXPECT_LT((covariance - expected).cwiseAbs().maxCoeff(), 1e-12) << covariance;
  EXPECT_TRUE(RelativeCovariance(graph, 1, 1)->isZero());
}

TEST(RelativeCovariance, WalkedBackwardsItIsTheCovarianceOfTheInversePosture) {
  // A bending chain whose edges have correlated covariances.
  PoseGraph graph;
  graph.AddNode(Pose2D(1.0, -2.0, 0.4));
  Eigen::Matrix3d covariance;
  covariance << 4e-4, 1e-4, 2e-5, 1e-4, 9e-4, -3e-5, 2e-5, -3e-5, 2e-4;
  for (std::size_t i = 1; i < 6; ++i) {
    const Pose2D step(0.8, 0.1 * static_cast<double>(i), 0.3);
    graph.AddNode(graph.nodes().back() * step);
    graph.AddEdge({i - 1, i, step, covariance.inverse(), EdgeKind::kSequential});
  }
  const Eigen::Matrix3d forward = *RelativeCovariance(graph, 0, 5);
  const Eigen::Matrix3d backward = *RelativeCovariance(graph, 5, 0);
  const Eigen::Matrix3d J = InverseJacobian(Between(graph.nodes()[0], graph.nodes()[5]));
  EXPECT_LT((backward - J * forward * J.transpose()).cwiseAbs().maxCoeff(), 1e-12)
      << backward << "\n"
      << J * forward * J.transpose();
  // Headings add up; positions gain the headings' lever on top of the five steps' own.
  EXPECT_NEAR(forward(2, 2), 5 * covariance(2, 2), 1e-15);
  const double steps_own = 5 * (covariance(0, 0) + covariance(1, 1));
  EXPECT_GT(forward(0, 0) + forward(1, 1), steps_own);
}

TEST(RelativeCovariance, AClosureShortensThePathAndUnjoinedNodesHaveNone) {
  PoseGraph graph = StraightChain(10, Diagonal(1e-2, 1e-2, 1e-2));
  const Eigen::Matrix3d closure = Diagonal(1e-4, 2e-4, 3e-5);
  const double chain_yy = (*RelativeCovariance(graph, 0, 9))(1, 1);
  graph.AddEdge({0, 9, Pose2D(9.0, 0.0, 0.0), closure.inverse(), EdgeKind::kClosure});
  EXPECT_LT((*RelativeCovariance(graph, 0, 9) - closure).cwiseAbs().maxCoeff(), 1e-12);
  EXPECT_GT(chain_yy, 1.0);  // nine steps of 0.1 rad heading error: metres² across
  // Node 8 is one chain step from the closure's end: its covariance is the closure's and a step.
  EXPECT_LT((*RelativeCovariance(graph, 0, 8))(0, 0), 0.02 + 1e-3);
  graph.AddNode(Pose2D(50.0, 0.0, 0.0));
  EXPECT_FALSE(RelativeCovariance(graph, 0, 10).has_value());
  EXPECT_THROW(RelativeCovariance(graph, 0, 11), std::invalid_argument);
}

TEST(RelativeCovariance, AnOdometryEdgeBesideASequentialOneAddsItsInformation) {
  const Eigen::Matrix3d sequential = Diagonal(4e-4, 1e-4, 2e-4);
  PoseGraph graph = StraightChain(4, sequential);
  const Eigen::Matrix3d alone = *RelativeCovariance(graph, 0, 3);
  // The same information again beside every step, one of them walked from its far end: each
  // step's covariance halves, and so does the chain's (first order, linear in the steps').
  for (std::size_t i = 1; i < 4; ++i) {
    if (i == 2)
      graph.AddEdge({i, i - 1, Pose2D(-1.0, 0.0, 0.0),
                     (InverseJacobian(Pose2D(1.0, 0.0, 0.0)) * sequential *
                      InverseJacobian(Pose2D(1.0, 0.0, 0.0)).transpose())
                         .inverse(),
                     EdgeKind::kOdometry});
    else
      graph.AddEdge({i - 1, i, Pose2D(1.0, 0.0, 0.0), sequential.inverse(), EdgeKind::kOdometry});
  }
  const Eigen::Matrix3d both = *RelativeCovariance(graph, 0, 3);
  EXPECT_LT((both - 0.5 * alone).cwiseAbs().maxCoeff(), 1e-12) << both << "\n" << alone;
  // An inactive edge adds nothing.
  graph.SetInformation(graph.edges().size() - 1, sequential.inverse(), false);
  EXPECT_GT((*RelativeCovariance(graph, 0, 3))(1, 1), both(1, 1));
}

}  // namespace
}  // namespace scanloc
