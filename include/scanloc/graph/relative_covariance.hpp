#pragma once
// How well a pose graph knows one node's posture relative to another: the covariance compounded
// along the path of fewest active edges between them (each edge's covariance is the inverse of its
// information, composed through the relative postures at the nodes' current estimates, first
// order). A loop closed since lowers it, because the path then runs through the closure.

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

}  // namespace scanloc
