#pragma once
// How well a pose graph knows one node's posture relative to another: the covariance compounded
// along the path of fewest active edges between them (each step's covariance is the inverse of
// the information of every active edge joining its two nodes, a sequential edge and an odometry
// edge beside it together, composed through the relative postures at the nodes' current
// estimates, first order). A loop closed since lowers it, because the path then runs through the
// closure.

#include <Eigen/Core>
#include <cstddef>
#include <optional>

#include "scanloc/graph/pose_graph.hpp"

namespace scanloc {

// The covariance of node `to`'s posture (x m, y m, yaw rad) seen from node `from`, in `from`'s
// frame; the zero matrix when they are the same node, nothing when no active edges join them.
// Throws std::invalid_argument for a node out of range.
std::optional<Eigen::Matrix3d> RelativeCovariance(const PoseGraph& graph, std::size_t from,
                                                  std::size_t to);

// A covariance given in a frame at heading `yaw_rad`, seen in the frame that frame lies in.
Eigen::Matrix3d RotatedOutOf(const Eigen::Matrix3d& covariance, double yaw_rad);

// The information of an edge from a node at heading `from_yaw_rad`, measured with a covariance
// given in the world (a refinement's, when it has one) rotated into that node's frame, plus the
// floors' variances.
Eigen::Matrix3d EdgeInformation(const std::optional<Eigen::Matrix3d>& covariance_world,
                                double from_yaw_rad, double floor_m, double floor_rad);

// A posture compounded from relative steps, T_start_end, with its covariance (x m, y m, yaw rad,
// in the start's frame) to first order: Σ ← J Σ Jᵀ + R Σ_step Rᵀ, J carrying the heading error so
// far over the step's displacement, R the end's heading.
struct CompoundedPosture {
  Pose2D T_start_end;
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  // Moves the end by `step` (T_end_next), whose covariance is given in the end's frame.
  void Append(const Pose2D& step, const Eigen::Matrix3d& step_covariance);
};

}  // namespace scanloc
