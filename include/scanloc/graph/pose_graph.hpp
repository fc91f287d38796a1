#pragma once
// A pose graph over SE(2): nodes are postures in the world, edges are measured relative postures
// with their information (inverse covariance). Optimise moves the nodes to agree with the edges in
// the least-squares sense (Ceres: yaw kept on its circle by a manifold, one node held fixed as the
// gauge). Closures pass through a Huber loss, so that a wrong one pulls with a bounded force, and
// after each solve the closure that disagrees most is set aside when its χ² fails the test, and
// the graph solved again: one wrong closure cannot bend the map.

#include <Eigen/Core>
#include <cstddef>
#include <string>
#include <vector>

#include "scanloc/geometry/pose2d.hpp"

namespace scanloc {

// Where an edge's measurement comes from. Only closures are robustified: sequential and odometry
// edges hold the chain together and are trusted as measured (a Huber loss on the odometry alone
// made it lose every disagreement with the matched step beyond a few σ, where the closures are
// the judge: docs/BENCHMARKS.md, "The odometry learned per log").
enum class EdgeKind { kSequential, kOdometry, kClosure };

const char* EdgeKindName(EdgeKind kind);

struct PoseGraphEdge {
  std::size_t from = 0;
  std::size_t to = 0;
  Pose2D T_from_to;  // the measured posture of `to` in `from`'s frame
  // Inverse covariance of (x m, y m, yaw rad) in `from`'s frame: symmetric positive definite.
  Eigen::Matrix3d information = Eigen::Matrix3d::Identity();
  EdgeKind kind = EdgeKind::kSequential;
  // False once Optimise has set the closure aside as inconsistent with the rest of the graph.
  bool active = true;
};

struct PoseGraphOptions {
  // Scale of the Huber loss on closure edges, in standard deviations of the whitened residual:
  // beyond it a closure pulls with a constant force. 0 turns the loss off (plain least squares).
  double closure_loss_scale = 3.0;
  // A closure whose squared whitened error stays above this after a solve is set aside (χ² with
  // 3 degrees of freedom: 16.27 is its 99.9 % quantile). 0 keeps every closure.
  double closure_rejection_chi2 = 16.27;
  int max_iterations = 100;
  std::size_t fixed_node = 0;  // the gauge: this node does not move
};

struct PoseGraphSummary {
  bool converged = false;
  int iterations = 0;
  double initial_cost = 0.0;  // ½ Σ ρ(‖r‖²) over all edges, Ceres' convention
  double final_cost = 0.0;
  int solves = 0;                     // one, plus one after each closure set aside
  std::size_t closures_rejected = 0;  // by this call
};

class PoseGraph {
 public:
  // Adds a node at `T_world_node` and returns its index. Throws std::invalid_argument for a pose
  // that is not finite.
  std::size_t AddNode(const Pose2D& T_world_node);
  // Throws std::invalid_argument for an unknown node, an edge from a node to itself, a measurement
  // that is not finite, or an information matrix that is not symmetric positive definite.
  void AddEdge(const PoseGraphEdge& edge);
  void SetNode(std::size_t index, const Pose2D& T_world_node);
  // Replaces edge `index`'s measurement (a node moved after its edge was laid). Throws
  // std::invalid_argument for an unknown edge.
  void SetMeasurement(std::size_t index, const Pose2D& T_from_to);
  // Replaces edge `index`'s information (the odometry's, once learned again), and whether it is
  // active. Throws std::invalid_argument for an unknown edge or an information that is not
  // symmetric positive definite.
  void SetInformation(std::size_t index, const Eigen::Matrix3d& information, bool active = true);

  const std::vector<Pose2D>& nodes() const { return nodes_; }
  const std::vector<PoseGraphEdge>& edges() const { return edges_; }

  // Solves the graph from the current node postures; the nodes hold the result and rejected
  // closures are marked inactive. A graph without edges returns at once. Throws
  // std::invalid_argument for a fixed node out of range. With hold_before > 0 the nodes before it
  // are held where they are (they are the gauge), and only the edges that touch a later node are
  // solved and tested: the part of the graph a new closure from node hold_before on moves most.
  PoseGraphSummary Optimise(const PoseGraphOptions& options = {}, std::size_t hold_before = 0);

  // The squared whitened error of `edge` at the current node postures: rᵀ Ω r with r the
  // difference between the measured and the current relative posture. Distributed as χ² with 3
  // degrees of freedom when the edge is right and its information honest.
  double SquaredError(const PoseGraphEdge& edge) const;

 private:
  std::vector<Pose2D> nodes_;
  std::vector<PoseGraphEdge> edges_;

  // One Ceres solve over the active edges.
  void Solve(const PoseGraphOptions& options, std::size_t hold_before, PoseGraphSummary& summary);
};

}  // namespace scanloc
