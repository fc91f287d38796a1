#include "scanloc/graph/relative_covariance.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <deque>
#include <limits>
#include <stdexcept>
#include <string>
#include <vector>

namespace scanloc {
namespace {

constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();

// One step of the path: the edge taken and whether it is walked from its `from` to its `to`.
struct Step {
  std::size_t edge = kNone;
  bool forward = true;
};

// The active edges touching each node, in the order of the graph's edges, in one flat array:
// node n's are edges[first[n] … first[n + 1]).
struct Touching {
  std::vector<std::size_t> first, edges;
};

Touching ActiveEdgesByNode(const PoseGraph& graph) {
  const std::vector<PoseGraphEdge>& edges = graph.edges();
  Touching touching;
  touching.first.assign(graph.nodes().size() + 1, 0);
  for (const PoseGraphEdge& edge : edges)
    if (edge.active) {
      ++touching.first[edge.from + 1];
      ++touching.first[edge.to + 1];
    }
  for (std::size_t n = 1; n < touching.first.size(); ++n)
    touching.first[n] += touching.first[n - 1];
  touching.edges.resize(touching.first.back());
  std::vector<std::size_t> next(touching.first.begin(), touching.first.end() - 1);
  for (std::size_t e = 0; e < edges.size(); ++e)
    if (edges[e].active) {
      touching.edges[next[edges[e].from]++] = e;
      touching.edges[next[edges[e].to]++] = e;
    }
  return touching;
}

// The steps of the path of fewest active edges from `from` to `to` (breadth first), in order;
// nothing when no path joins them.
std::optional<std::vector<Step>> FewestEdges(const PoseGraph& graph, std::size_t from,
                                             std::size_t to) {
  const std::vector<PoseGraphEdge>& edges = graph.edges();
  const Touching touching = ActiveEdgesByNode(graph);
  std::vector<Step> reached_by(graph.nodes().size());
  std::vector<bool> seen(graph.nodes().size(), false);
  std::deque<std::size_t> frontier = {from};
  seen[from] = true;
  while (!frontier.empty() && !seen[to]) {
    const std::size_t node = frontier.front();
    frontier.pop_front();
    for (std::size_t k = touching.first[node]; k < touching.first[node + 1]; ++k) {
      const std::size_t e = touching.edges[k];
      const bool forward = edges[e].from == node;
      const std::size_t next = forward ? edges[e].to : edges[e].from;
      if (seen[next]) continue;
      seen[next] = true;
      reached_by[next] = {e, forward};
      frontier.push_back(next);
    }
  }
  if (!seen[to]) return std::nullopt;
  std::vector<Step> path;
  for (std::size_t node = to; node != from;) {
    const Step step = reached_by[node];
    path.push_back(step);
    node = step.forward ? edges[step.edge].from : edges[step.edge].to;
  }
  std::reverse(path.begin(), path.end());
  return path;
}

// The covariance of an edge's measurement walked from `to` back to `from`: that of the inverse
// posture, through the inverse's Jacobian at the edge's current relative posture T.
Eigen::Matrix3d InverseCovariance(const Pose2D& T, const Eigen::Matrix3d& covariance) {
  const double c = std::cos(T.yaw_rad), s = std::sin(T.yaw_rad);
  Eigen::Matrix3d jacobian;
  jacobian << -c, -s, s * T.x_m - c * T.y_m, s, -c, c * T.x_m + s * T.y_m, 0.0, 0.0, -1.0;
  return jacobian * covariance * jacobian.transpose();
}

}  // namespace

Eigen::Matrix3d RotatedOutOf(const Eigen::Matrix3d& covariance, double yaw_rad) {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  rotation.topLeftCorner<2, 2>() << std::cos(yaw_rad), -std::sin(yaw_rad), std::sin(yaw_rad),
      std::cos(yaw_rad);
  return rotation * covariance * rotation.transpose();
}

std::optional<Eigen::Matrix3d> RelativeCovariance(const PoseGraph& graph, std::size_t from,
                                                  std::size_t to) {
  const std::vector<Pose2D>& nodes = graph.nodes();
  if (from >= nodes.size() || to >= nodes.size())
    throw std::invalid_argument("RelativeCovariance: node " + std::to_string(std::max(from, to)) +
                                " out of range (" + std::to_string(nodes.size()) + " nodes)");
  const std::optional<std::vector<Step>> path = FewestEdges(graph, from, to);
  if (!path) return std::nullopt;
  // Σₖ = J Σₖ₋₁ Jᵀ + R Σ_step Rᵀ: the posture so far moved by one step, whose covariance is given
  // in the frame of the node it starts from.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  std::size_t at = from;
  for (const Step& step : *path) {
    const PoseGraphEdge& edge = graph.edges()[step.edge];
    const std::size_t next = step.forward ? edge.to : edge.from;
    Eigen::Matrix3d step_covariance = edge.information.inverse();
    if (!step.forward)
      step_covariance =
          InverseCovariance(Between(nodes[edge.from], nodes[edge.to]), step_covariance);
    const Pose2D before = Between(nodes[from], nodes[at]);
    const Pose2D after = Between(nodes[from], nodes[next]);
    Eigen::Matrix3d jacobian = Eigen::Matrix3d::Identity();
    jacobian(0, 2) = -(after.y_m - before.y_m);
    jacobian(1, 2) = after.x_m - before.x_m;
    covariance = jacobian * covariance * jacobian.transpose() +
                 RotatedOutOf(step_covariance, before.yaw_rad);
    at = next;
  }
  return 0.5 * (covariance + covariance.transpose());
}

}  // namespace scanloc
