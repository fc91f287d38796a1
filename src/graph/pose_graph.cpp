#include "scanloc/graph/pose_graph.hpp"

#include <ceres/ceres.h>

#include <Eigen/Cholesky>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <string>

#include "pose_graph_terms.hpp"

namespace scanloc {
namespace {

// The upper factor U of Ω = UᵀU, or an empty optional-like zero matrix when Ω is not symmetric
// positive definite.
bool SquareRootInformation(const Eigen::Matrix3d& information, Eigen::Matrix3d& root) {
  if (!information.allFinite() || !information.isApprox(information.transpose(), 1e-9))
    return false;
  const Eigen::LLT<Eigen::Matrix3d> llt(information);
  if (llt.info() != Eigen::Success) return false;
  root = llt.matrixU();
  return root.allFinite() && root.diagonal().minCoeff() > 0.0;
}

bool IsFinite(const Pose2D& pose) {
  return std::isfinite(pose.x_m) && std::isfinite(pose.y_m) && std::isfinite(pose.yaw_rad);
}

}  // namespace

const char* EdgeKindName(EdgeKind kind) {
  switch (kind) {
    case EdgeKind::kSequential:
      return "sequential";
    case EdgeKind::kOdometry:
      return "odometry";
    case EdgeKind::kClosure:
      return "closure";
  }
  return "unknown";
}

std::size_t PoseGraph::AddNode(const Pose2D& T_world_node) {
  if (!IsFinite(T_world_node)) throw std::invalid_argument("pose graph node is not finite");
  nodes_.push_back(T_world_node.Normalized());
  return nodes_.size() - 1;
}

void PoseGraph::SetNode(std::size_t index, const Pose2D& T_world_node) {
  if (index >= nodes_.size())
    throw std::invalid_argument("no pose graph node " + std::to_string(index));
  if (!IsFinite(T_world_node)) throw std::invalid_argument("pose graph node is not finite");
  nodes_[index] = T_world_node.Normalized();
}

void PoseGraph::SetMeasurement(std::size_t index, const Pose2D& T_from_to) {
  if (index >= edges_.size())
    throw std::invalid_argument("no pose graph edge " + std::to_string(index));
  if (!IsFinite(T_from_to)) throw std::invalid_argument("pose graph measurement is not finite");
  edges_[index].T_from_to = T_from_to.Normalized();
}

void PoseGraph::AddEdge(const PoseGraphEdge& edge) {
  const std::string name =
      "pose graph edge " + std::to_string(edge.from) + " → " + std::to_string(edge.to);
  if (edge.from >= nodes_.size() || edge.to >= nodes_.size())
    throw std::invalid_argument(name + " names a node the graph does not have (" +
                                std::to_string(nodes_.size()) + " nodes)");
  if (edge.from == edge.to) throw std::invalid_argument(name + " links a node to itself");
  if (!IsFinite(edge.T_from_to)) throw std::invalid_argument(name + " is not finite");
  Eigen::Matrix3d root;
  if (!SquareRootInformation(edge.information, root))
    throw std::invalid_argument(name + ": information is not symmetric positive definite");
  edges_.push_back(edge);
}

void PoseGraph::SetInformation(std::size_t index, const Eigen::Matrix3d& information, bool active) {
  if (index >= edges_.size())
    throw std::invalid_argument("no pose graph edge " + std::to_string(index));
  Eigen::Matrix3d root;
  if (!SquareRootInformation(information, root))
    throw std::invalid_argument("pose graph edge " + std::to_string(index) +
                                ": information is not symmetric positive definite");
  edges_[index].information = information;
  edges_[index].active = active;
}

double PoseGraph::SquaredError(const PoseGraphEdge& edge) const {
  const Pose2D now = Between(nodes_.at(edge.from), nodes_.at(edge.to));
  const Eigen::Vector3d error(now.x_m - edge.T_from_to.x_m, now.y_m - edge.T_from_to.y_m,
                              NormalizeAngle(now.yaw_rad - edge.T_from_to.yaw_rad));
  return error.dot(edge.information * error);
}

PoseGraphSummary PoseGraph::Optimise(const PoseGraphOptions& options, std::size_t hold_before) {
  if (options.fixed_node >= nodes_.size() && !nodes_.empty())
    throw std::invalid_argument("fixed pose graph node " + std::to_string(options.fixed_node) +
                                " out of range (" + std::to_string(nodes_.size()) + " nodes)");
  PoseGraphSummary summary;
  summary.converged = true;
  if (edges_.empty()) return summary;
  hold_before = std::min(hold_before, nodes_.size() - 1);
  for (;;) {
    Solve(options, hold_before, summary);
    if (options.closure_rejection_chi2 <= 0.0) break;
    PoseGraphEdge* worst = nullptr;
    double worst_chi2 = options.closure_rejection_chi2;
    for (PoseGraphEdge& edge : edges_) {
      if (edge.kind != EdgeKind::kClosure || !edge.active ||
          std::max(edge.from, edge.to) < hold_before)
        continue;
      const double chi2 = SquaredError(edge);
      if (chi2 > worst_chi2) {
        worst = &edge;
        worst_chi2 = chi2;
      }
    }
    if (worst == nullptr) break;
    worst->active = false;
    ++summary.closures_rejected;
  }
  return summary;
}

void PoseGraph::Solve(const PoseGraphOptions& options, std::size_t hold_before,
                      PoseGraphSummary& summary) {
  std::vector<double> postures(3 * nodes_.size());
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    postures[3 * i] = nodes_[i].x_m;
    postures[3 * i + 1] = nodes_[i].y_m;
    postures[3 * i + 2] = nodes_[i].yaw_rad;
  }
  // One manifold and one loss shared by every block: the problem must not delete them.
  PostureManifold manifold;
  ceres::HuberLoss closure_loss(options.closure_loss_scale > 0.0 ? options.closure_loss_scale
                                                                 : 1.0);
  ceres::Problem::Options problem_options;
  problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  problem_options.loss_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  ceres::Problem problem(problem_options);
  for (const PoseGraphEdge& edge : edges_) {
    if (!edge.active || std::max(edge.from, edge.to) < hold_before) continue;
    Eigen::Matrix3d root;
    SquareRootInformation(edge.information, root);
    auto* cost = new RelativePostureCost(edge.T_from_to, root);
    const bool robust = edge.kind == EdgeKind::kClosure && options.closure_loss_scale > 0.0;
    problem.AddResidualBlock(cost, robust ? &closure_loss : nullptr, &postures[3 * edge.from],
                             &postures[3 * edge.to]);
  }
  for (std::size_t i = 0; i < nodes_.size(); ++i)
    if (problem.HasParameterBlock(&postures[3 * i]))
      problem.SetManifold(&postures[3 * i], &manifold);
  const std::size_t gauge = options.fixed_node;
  if (problem.HasParameterBlock(&postures[3 * gauge]))
    problem.SetParameterBlockConstant(&postures[3 * gauge]);
  for (std::size_t i = 0; i < hold_before; ++i)
    if (problem.HasParameterBlock(&postures[3 * i]))
      problem.SetParameterBlockConstant(&postures[3 * i]);
  ceres::Solver::Options solver;
  solver.linear_solver_type = ceres::SPARSE_NORMAL_CHOLESKY;
  solver.max_num_iterations = options.max_iterations;
  solver.num_threads = 1;
  solver.logging_type = ceres::SILENT;
  ceres::Solver::Summary result;
  ceres::Solve(solver, &problem, &result);
  if (summary.solves++ == 0) summary.initial_cost = result.initial_cost;
  summary.converged = result.termination_type == ceres::CONVERGENCE;
  summary.iterations += static_cast<int>(result.iterations.size());
  summary.final_cost = result.final_cost;
  for (std::size_t i = 0; i < nodes_.size(); ++i)
    nodes_[i] = Pose2D(postures[3 * i], postures[3 * i + 1], postures[3 * i + 2]).Normalized();
}

}  // namespace scanloc
