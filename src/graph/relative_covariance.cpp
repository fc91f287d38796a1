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

// The nodes of the path of fewest active edges from `from` to `to` (breadth first), both
// included, in order; nothing when no path joins them.
std::optional<std::vector<std::size_t>> FewestEdges(const PoseGraph& graph,
                                                    const Touching& touching, std::size_t from,
                                                    std::size_t to) {
  const std::vector<PoseGraphEdge>& edges = graph.edges();
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
  std::vector<std::size_t> path = {to};
  for (std::size_t node = to; node != from;) {
    const Step step = reached_by[node];
    node = step.forward ? edges[step.edge].from : edges[step.edge].to;
    path.push_back(node);
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

// The covariance of node `next`'s posture in node `at`'s frame from every active edge joining
// the two (their informations summed, each edge walked backwards seen forwards).
Eigen::Matrix3d StepCovariance(const PoseGraph& graph, const Touching& touching, std::size_t at,
                               std::size_t next) {
  const std::vector<Pose2D>& nodes = graph.nodes();
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  for (std::size_t k = touching.first[at]; k < touching.first[at + 1]; ++k) {
    const PoseGraphEdge& edge = graph.edges()[touching.edges[k]];
    if (edge.from == at && edge.to == next) {
      information += edge.information;
    } else if (edge.from == next && edge.to == at) {
      information +=
          InverseCovariance(Between(nodes[next], nodes[at]), edge.information.inverse()).inverse();
    }
  }
  return information.inverse();
}

}  // namespace

Eigen::Matrix3d RotatedOutOf(const Eigen::Matrix3d& covariance, double yaw_rad) {
  Eigen::Matrix3d rotation = Eigen::Matrix3d::Identity();
  rotation.topLeftCorner<2, 2>() << std::cos(yaw_rad), -std::sin(yaw_rad), std::sin(yaw_rad),
      std::cos(yaw_rad);
  return rotation * covariance * rotation.transpose();
}

Eigen::Matrix3d EdgeInformation(const std::optional<Eigen::Matrix3d>& covariance_world,
                                double from_yaw_rad, double floor_m, double floor_rad) {
  Eigen::Matrix3d covariance =
      Eigen::Vector3d(floor_m * floor_m, floor_m * floor_m, floor_rad * floor_rad).asDiagonal();
  if (covariance_world && covariance_world->allFinite())
    covariance += RotatedOutOf(*covariance_world, -from_yaw_rad);
  Eigen::Matrix3d information = covariance.inverse();
  return 0.5 * (information + information.transpose());
}

void CompoundedPosture::Append(const Pose2D& step, const Eigen::Matrix3d& step_covariance) {
  const Pose2D after = T_start_end * step;
  Eigen::Matrix3d jacobian = Eigen::Matrix3d::Identity();
  jacobian(0, 2) = -(after.y_m - T_start_end.y_m);
  jacobian(1, 2) = after.x_m - T_start_end.x_m;
  covariance = jacobian * covariance * jacobian.transpose() +
               RotatedOutOf(step_covariance, T_start_end.yaw_rad);
  T_start_end = after;
}

std::optional<Eigen::Matrix3d> RelativeCovariance(const PoseGraph& graph, std::size_t from,
                                                  std::size_t to) {
  const std::vector<Pose2D>& nodes = graph.nodes();
  if (from >= nodes.size() || to >= nodes.size())
    throw std::invalid_argument("RelativeCovariance: node " + std::to_string(std::max(from, to)) +
                                " out of range (" + std::to_string(nodes.size()) + " nodes)");
  const Touching touching = ActiveEdgesByNode(graph);
  const std::optional<std::vector<std::size_t>> path = FewestEdges(graph, touching, from, to);
  if (!path) return std::nullopt;
  // The steps compounded at the nodes' current estimates, each from the node it starts at.
  CompoundedPosture compounded;
  for (std::size_t k = 0; k + 1 < path->size(); ++k) {
    const std::size_t at = (*path)[k], next = (*path)[k + 1];
    compounded.Append(Between(nodes[at], nodes[next]), StepCovariance(graph, touching, at, next));
  }
  return 0.5 * (compounded.covariance + compounded.covariance.transpose());
}

}  // namespace scanloc
