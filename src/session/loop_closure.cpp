#include "scanloc/session/loop_closure.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <utility>

#include "scanloc/graph/relative_covariance.hpp"

namespace scanloc {
namespace {

double Distance(const Pose2D& a, const Pose2D& b) {
  return (a.Translation() - b.Translation()).norm();
}

// The odometry holds a motion's heading when the model says it knows it at least as well as a
// matched step knows its own (in the graph's units). Only then does its edge join the graph: an
// odometry weaker than the matching in heading would add little, and what its model does not
// describe (slips in fast turns, drifts that grow with the path) would bend the chain by many
// small consistent pulls. The heading is what carries a chain off; the model's position noise,
// fitted on stretches, still holds some of the matching's own jitter.
bool OdometryHoldsHeading(const Eigen::Matrix3d& odometry_covariance,
                          const Eigen::Matrix3d& matched_covariance) {
  return odometry_covariance(2, 2) <= matched_covariance(2, 2);
}

// Another valid refinement lies farther than distinct_m or distinct_rad from the kept one.
bool Ambiguous(const LocalisationResult& result, const RankedCandidate& kept, double distinct_m,
               double distinct_rad) {
  for (const RankedCandidate& other : result.refined) {
    if (other.verdict != Verdict::kValid) continue;
    const Pose2D d = Between(kept.T_world_robot, other.T_world_robot);
    if (std::hypot(d.x_m, d.y_m) > distinct_m || std::abs(NormalizeAngle(d.yaw_rad)) > distinct_rad)
      return true;
  }
  return false;
}

// The largest standard deviation of the position part of a covariance.
double LargestSigmaM(const Eigen::Matrix3d& covariance) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> eigen(covariance.topLeftCorner<2, 2>());
  return std::sqrt(std::max(0.0, eigen.eigenvalues().maxCoeff()));
}

// What a solve would do with one closure edge, to first order: the correction of the edge's
// relative posture (the chain's covariance against the closure's, the Kalman gain) and the
// closure's squared Mahalanobis innovation. Nothing when no active path joins its nodes.
struct PredictedCorrection {
  Eigen::Vector3d correction;  // x m, y m, yaw rad in the old node's frame
  double chi2 = 0.0;
};
std::optional<PredictedCorrection> Predict(const PoseGraph& graph, const PoseGraphEdge& edge) {
  const std::optional<Eigen::Matrix3d> chain = RelativeCovariance(graph, edge.from, edge.to);
  if (!chain) return std::nullopt;
  const Pose2D now = Between(graph.nodes()[edge.from], graph.nodes()[edge.to]);
  const Eigen::Vector3d innovation(edge.T_from_to.x_m - now.x_m, edge.T_from_to.y_m - now.y_m,
                                   NormalizeAngle(edge.T_from_to.yaw_rad - now.yaw_rad));
  const Eigen::Matrix3d total_inverse = (*chain + edge.information.inverse()).inverse();
  return PredictedCorrection{*chain * total_inverse * innovation,
                             innovation.dot(total_inverse * innovation)};
}

}  // namespace

void LoopClosureOptions::Validate() const {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("LoopClosureOptions: ") + what);
  };
  require(min_path_m >= 0.0, "min_path_m must be >= 0");
  require(local_map_radius_m > 0.0, "local_map_radius_m must be positive");
  require(min_local_nodes >= 1, "min_local_nodes must be >= 1");
  require(attempt_every_nodes >= 1 && attempt_every_m >= 0.0,
          "attempt_every_nodes must be >= 1 and attempt_every_m >= 0");
  require(min_half_width_m >= 0.0 && max_half_width_m >= min_half_width_m,
          "0 <= min_half_width_m <= max_half_width_m");
  require(translation_error_per_m >= 0.0 && heading_error_per_m >= 0.0,
          "error growth rates must be >= 0");
  require(
      min_half_yaw_rad >= 0.0 && max_half_yaw_rad >= min_half_yaw_rad && max_half_yaw_rad <= M_PI,
      "0 <= min_half_yaw_rad <= max_half_yaw_rad <= π");
  require(window_sigmas >= 0.0, "window_sigmas must be >= 0");
  search.Validate();
  require(max_sigma_m > 0.0, "max_sigma_m must be positive");
  require(max_local_nodes >= min_local_nodes, "max_local_nodes must be >= min_local_nodes");
  require(distinct_m >= 0.0 && distinct_rad >= 0.0, "distinct_m and distinct_rad must be >= 0");
  require(confirm_after >= 1, "confirm_after must be >= 1");
  require(agree_m >= 0.0 && agree_rad >= 0.0, "agree_m and agree_rad must be >= 0");
  require(dispute_turn_of_bound >= 0.0, "dispute_turn_of_bound must be >= 0");
  require(sigma_floor_m > 0.0 && sigma_floor_rad > 0.0, "sigma floors must be positive");
  require(graph.closure_loss_scale >= 0.0 && graph.closure_rejection_chi2 >= 0.0 &&
              graph.max_iterations >= 1,
          "graph: loss scale and rejection χ² >= 0, max_iterations >= 1");
  require(render_min_shift_m >= 0.0, "render_min_shift_m must be >= 0");
  require(tracking_path_m >= 0.0 && tracking_min_nodes >= 0,
          "tracking_path_m and tracking_min_nodes must be >= 0");
  odometry.Validate();
  final_match.Validate();
}

LoopCloser::LoopCloser(const LoopClosureOptions& options, const LaserMounting& mounting)
    : options_(options), mounting_(mounting), odometry_model_(options.odometry) {
  options_.Validate();
}

void LoopCloser::AddNode(std::size_t iteration, const LaserScan& scan, const Pose2D& T_world_robot,
                         const std::optional<Eigen::Matrix3d>& laser_covariance,
                         const std::optional<Pose2D>& odometry) {
  double path_m = 0.0;
  if (!nodes_.empty())
    path_m = nodes_.back().path_m + Distance(graph_.nodes().back(), T_world_robot);
  nodes_.push_back({iteration, scan, path_m, odometry, 0, Eigen::Matrix3d::Zero(), std::nullopt});
  const std::size_t node = graph_.AddNode(T_world_robot);
  ++nodes_since_attempt_;
  if (node == 0) return;
  const Pose2D& from = graph_.nodes()[node - 1];
  nodes_.back().sequential_edge = graph_.edges().size();
  graph_.AddEdge({node - 1, node, Between(from, graph_.nodes()[node]),
                  EdgeInformation(laser_covariance, from.yaw_rad, options_.sigma_floor_m,
                                  options_.sigma_floor_rad),
                  EdgeKind::kSequential});
  nodes_.back().sequential_covariance = graph_.edges().back().information.inverse();
  if (odometry_model_.learned()) WeighOdometry(node);
}

void LoopCloser::MoveNewestNode(const Pose2D& T_world_robot) {
  if (nodes_.empty()) throw std::logic_error("LoopCloser::MoveNewestNode: no node");
  const std::size_t node = nodes_.size() - 1;
  graph_.SetNode(node, T_world_robot);
  if (node > 0) {
    const Pose2D& before = graph_.nodes()[node - 1];
    graph_.SetMeasurement(nodes_.back().sequential_edge, Between(before, graph_.nodes()[node]));
    nodes_.back().path_m = nodes_[node - 1].path_m + Distance(before, graph_.nodes()[node]);
  }
  // The pending run's correction, measured from where the node was, now from where it is.
  if (!pending_.empty() && pending_.back().to == node && !attempts_.empty() &&
      attempts_.back().node == node)
    pending_correction_ = attempts_.back().T_world_robot_matched * T_world_robot.Inverse();
}

void LoopCloser::Anchor(std::size_t iteration, const Pose2D& T_world_robot, bool confirmed,
                        const std::optional<Pose2D>& odometry,
                        const std::optional<AnchorTiming>& timing) {
  if (nodes_.empty()) return;
  if (anchors_.size() <= iteration) anchors_.resize(iteration + 1);
  const std::size_t node = nodes_.size() - 1;
  Anchoring& anchor = anchors_[iteration].emplace();
  anchor.node = node;
  anchor.T_node_robot = Between(graph_.nodes()[node], T_world_robot);
  anchor.timing = timing;
  anchor.kept_prediction =
      !confirmed && timing && !timing->skipped && SamePosture(T_world_robot, timing->prediction);
  if (!confirmed && odometry && nodes_[node].odometry)
    anchor.T_node_robot_odometry = Between(*nodes_[node].odometry, *odometry);
  // No solve has moved the skipped scans' node since they were anchored to it.
  const auto carried = [&](std::size_t i) {
    return Skipped(i) ||
           (options_.spread_over_unconfirmed && anchors_[i] && anchors_[i]->kept_prediction);
  };
  if (timing && !timing->skipped && iteration > 0 && carried(iteration - 1)) {
    anchor.prediction_node = anchors_[iteration - 1]->node;
    anchor.T_node_prediction = Between(graph_.nodes()[*anchor.prediction_node], timing->prediction);
  }
}

bool LoopCloser::Skipped(std::size_t iteration) const {
  return iteration < anchors_.size() && anchors_[iteration] && anchors_[iteration]->timing &&
         anchors_[iteration]->timing->skipped;
}

// A skipped scan, or with spread_over_unconfirmed an unconfirmed one that kept its prediction and
// does not follow the odometry from its node: it takes a share of the next localised scan's
// correction.
bool LoopCloser::SharesNextCorrection(std::size_t iteration) const {
  if (Skipped(iteration)) return true;
  if (!options_.spread_over_unconfirmed || iteration >= anchors_.size() || !anchors_[iteration])
    return false;
  return anchors_[iteration]->kept_prediction && !ByOdometry(*anchors_[iteration]);
}

// The old nodes the scan is matched on: the nearest node old enough, and the nodes laid just
// before and after it (at most max_local_nodes in all, all old enough and within the radius). One
// stretch of one pass: its nodes agree with each other, where nodes of several passes would not
// until their loops are closed. Empty when fewer than min_local_nodes.
std::vector<std::size_t> LoopCloser::OldNodesNear(const Pose2D& T_world_robot,
                                                  double path_m) const {
  auto usable = [&](std::size_t i) {
    return path_m - nodes_[i].path_m >= options_.min_path_m &&
           Distance(graph_.nodes()[i], T_world_robot) <= options_.local_map_radius_m;
  };
  std::optional<std::size_t> nearest;
  for (std::size_t i = 0; i < nodes_.size() && path_m - nodes_[i].path_m >= options_.min_path_m;
       ++i)
    if (usable(i) && (!nearest || Distance(graph_.nodes()[i], T_world_robot) <
                                      Distance(graph_.nodes()[*nearest], T_world_robot)))
      nearest = i;
  if (!nearest) return {};
  std::vector<std::size_t> stretch = {*nearest};
  const std::size_t wanted = static_cast<std::size_t>(options_.max_local_nodes);
  for (std::size_t step = 1; stretch.size() < wanted; ++step) {
    const bool before = step <= *nearest && usable(*nearest - step);
    const bool after = *nearest + step < nodes_.size() && usable(*nearest + step);
    if (!before && !after) break;
    if (before) stretch.push_back(*nearest - step);
    if (after && stretch.size() < wanted) stretch.push_back(*nearest + step);
  }
  if (stretch.size() < static_cast<std::size_t>(options_.min_local_nodes)) return {};
  return stretch;
}

std::optional<ClosureAttempt> LoopCloser::MaybeClose(const LocalisationOptions& localisation,
                                                     const PointMapOptions& map_options) {
  if (!options_.enabled || nodes_.empty()) return std::nullopt;
  const bool due =
      !pending_.empty() ||
      (nodes_since_attempt_ >= static_cast<std::size_t>(options_.attempt_every_nodes) &&
       nodes_.back().path_m - path_at_attempt_m_ >= options_.attempt_every_m);
  if (!due) return std::nullopt;
  nodes_since_attempt_ = 0;
  path_at_attempt_m_ = nodes_.back().path_m;
  const auto start = std::chrono::steady_clock::now();
  std::optional<ClosureAttempt> attempt = Try(localisation, map_options);
  if (!attempt) {
    pending_.clear();
    return std::nullopt;
  }
  attempt->time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  attempts_.push_back(*attempt);
  return attempt;
}

// Localises the newest node's scan against a map of the old nodes near it.
std::optional<ClosureAttempt> LoopCloser::Try(const LocalisationOptions& localisation,
                                              const PointMapOptions& map_options) {
  const std::size_t newest = nodes_.size() - 1;
  const Pose2D T_world_robot = graph_.nodes()[newest];
  const std::vector<std::size_t> old = OldNodesNear(T_world_robot, nodes_[newest].path_m);
  if (old.size() < static_cast<std::size_t>(options_.min_local_nodes)) return std::nullopt;
  ClosureAttempt attempt;
  attempt.iteration = nodes_[newest].iteration;
  attempt.node = newest;
  attempt.local_nodes = old.size();
  attempt.T_world_robot_before = T_world_robot;
  attempt.old_node = old.front();
  attempt.old_iteration = nodes_[attempt.old_node].iteration;
  attempt.path_since_m = nodes_[newest].path_m - nodes_[attempt.old_node].path_m;
  const MapView view{nullptr, &LocalMap(old, map_options)};
  const LaserScan& scan = nodes_[newest].scan;
  if (!FitWindow(attempt)) {
    pending_.clear();
    return attempt;
  }
  // A run's middle scans search the smallest window around where the run puts them (Confirm
  // measures agreement from there); its first and last search the whole window.
  attempt.from_run = options_.confirm_from_run && !pending_.empty() &&
                     pending_.size() + 1 < static_cast<std::size_t>(options_.confirm_after);
  std::vector<Candidate> candidates{{T_world_robot, "session"}};
  if (attempt.from_run) {
    candidates = RunCandidates(newest);
    attempt.window = {mounting_.LaserPose(candidates.front().T_world_robot),
                      options_.min_half_width_m, options_.min_half_yaw_rad};
  }
  const WideSearchResult search =
      WideSearch(view, scan, attempt.window, options_.search, &search_field_);
  for (std::size_t i = 0; i < search.candidates.size(); ++i)
    candidates.push_back(
        {mounting_.RobotPose(search.candidates[i].T_world_laser), "search" + std::to_string(i)});
  const LocalisationResult result =
      Localise(view, scan, candidates, mounting_, localisation, RefinePolicy::kBestValid, 3);
  if (!pending_.empty()) attempt.run_correction = pending_correction_;
  Judge(result, attempt);
  return attempt;
}

// Where the pending run puts the newest node: its correction applied to the session's posture,
// and the previous node's match moved on by the odometry between the two (which holds where the
// tracker turned the newest node wrong; a match refined from each that validated both, apart,
// is ambiguous).
std::vector<Candidate> LoopCloser::RunCandidates(std::size_t newest) const {
  std::vector<Candidate> candidates{{pending_correction_ * graph_.nodes()[newest], "run"}};
  const ClosureAttempt& previous = attempts_.back();
  if (previous.node + 1 == newest && nodes_[previous.node].odometry && nodes_[newest].odometry)
    candidates.push_back({previous.T_world_robot_matched *
                              Between(*nodes_[previous.node].odometry, *nodes_[newest].odometry),
                          "run+odometry"});
  return candidates;
}

// The map rendered from the old nodes `old` at their current postures: the last attempt's when it
// was made from the same nodes with the same options and no solve has moved them since.
const PointMap& LoopCloser::LocalMap(const std::vector<std::size_t>& old,
                                     const PointMapOptions& map_options) {
  const bool same = local_map_ && old == local_nodes_ && map_options == local_map_options_;
  if (same) return *local_map_;
  local_map_.emplace(map_options);
  for (const std::size_t i : old)
    local_map_->InsertScan(nodes_[i].scan, mounting_.LaserPose(graph_.nodes()[i]));
  local_nodes_ = old;
  local_map_options_ = map_options;
  return *local_map_;
}

// The window searched around the current posture, from the path driven since the old node or,
// with window_sigmas, from the graph's uncertainty of the current node relative to it. False (the
// reason given) when the uncertainty needs a wider window than the maxima allow.
bool LoopCloser::FitWindow(ClosureAttempt& attempt) const {
  const std::optional<Eigen::Matrix3d> relative =
      RelativeCovariance(graph_, attempt.old_node, attempt.node);
  if (relative) {
    attempt.chain_sigma_m = LargestSigmaM(*relative);
    attempt.chain_sigma_rad = std::sqrt(std::max(0.0, (*relative)(2, 2)));
  }
  double half_m =
      options_.min_half_width_m + options_.translation_error_per_m * attempt.path_since_m;
  double half_rad = options_.min_half_yaw_rad + options_.heading_error_per_m * attempt.path_since_m;
  if (options_.window_sigmas > 0.0) {
    half_m = std::max(options_.min_half_width_m, options_.window_sigmas * attempt.chain_sigma_m);
    half_rad =
        std::max(options_.min_half_yaw_rad, options_.window_sigmas * attempt.chain_sigma_rad);
    if (!relative || half_m > options_.max_half_width_m || half_rad > options_.max_half_yaw_rad) {
      attempt.reason = "too uncertain: the window needs ±" + std::to_string(half_m) + " m, ±" +
                       std::to_string(half_rad) + " rad";
      return false;
    }
  }
  attempt.window = {mounting_.LaserPose(attempt.T_world_robot_before),
                    std::min(options_.max_half_width_m, half_m),
                    std::min(options_.max_half_yaw_rad, half_rad)};
  return true;
}

// Accepts the localisation's kept posture as a closure when the rules validated it and the
// geometry pins it; the graph is then solved.
void LoopCloser::Judge(const LocalisationResult& result, ClosureAttempt& attempt) {
  const RankedCandidate* kept = result.Kept();
  if (kept == nullptr) {
    attempt.reason = "nothing was refined";
    return;
  }
  attempt.T_world_robot_matched = kept->T_world_robot;
  attempt.T_old_robot = Between(graph_.nodes()[attempt.old_node], kept->T_world_robot);
  attempt.test = kept->test;
  const RefinementResult& refinement = *kept->refinement;
  if (!result.validated()) {
    attempt.reason = std::string("not validated: ") + ToString(kept->verdict);
  } else if (refinement.degenerate) {
    attempt.reason = "degenerate: " + refinement.degeneracy;
  } else if (!refinement.has_covariance) {
    attempt.reason = "no covariance";
  } else if (LargestSigmaM(refinement.covariance) > options_.max_sigma_m) {
    attempt.reason = "not pinned: σ " + std::to_string(LargestSigmaM(refinement.covariance)) + " m";
  } else if (Ambiguous(result, *kept, options_.distinct_m, options_.distinct_rad)) {
    attempt.reason = "ambiguous: another distinct posture is valid too";
  } else {
    Confirm(refinement.covariance, attempt);
    return;
  }
  pending_.clear();
}

// A valid closure joins the pending ones when it agrees with their correction (or starts them
// anew); once confirm_after agree, their edges go into the graph and it is solved.
void LoopCloser::Confirm(const Eigen::Matrix3d& covariance, ClosureAttempt& attempt) {
  const Pose2D correction = attempt.T_world_robot_matched * attempt.T_world_robot_before.Inverse();
  if (!pending_.empty()) {
    const Pose2D disagreement =
        Between(pending_correction_ * attempt.T_world_robot_before, attempt.T_world_robot_matched);
    if (std::hypot(disagreement.x_m, disagreement.y_m) > options_.agree_m ||
        std::abs(NormalizeAngle(disagreement.yaw_rad)) > options_.agree_rad)
      pending_.clear();
  }
  if (pending_.empty()) pending_correction_ = correction;
  const Pose2D& from = graph_.nodes()[attempt.old_node];
  pending_.push_back(
      {attempt.old_node, attempt.node, attempt.T_old_robot,
       EdgeInformation(covariance, from.yaw_rad, options_.sigma_floor_m, options_.sigma_floor_rad),
       EdgeKind::kClosure});
  if (pending_.size() < static_cast<std::size_t>(options_.confirm_after)) {
    attempt.pending = true;
    attempt.reason = "pending: " + std::to_string(pending_.size()) + " of " +
                     std::to_string(options_.confirm_after) + " agreeing scans";
    return;
  }
  Solve(attempt);
}

// Whether the confirmed closures may join the graph unsolved: each one's predicted correction
// moves its node by less than render_min_shift_m, and the graph explains it (a closure it might
// set aside is solved at once). Records the largest predicted shift.
bool LoopCloser::SolveLater(ClosureAttempt& attempt) const {
  bool later = true;
  for (const PoseGraphEdge& pending : pending_) {
    const std::optional<PredictedCorrection> predicted = Predict(graph_, pending);
    if (!predicted) return false;
    const double shift_m = predicted->correction.head<2>().norm();
    attempt.predicted_shift_m = std::max(attempt.predicted_shift_m, shift_m);
    const double chi2_limit = options_.graph.closure_rejection_chi2;
    later = later && shift_m <= options_.render_min_shift_m &&
            (chi2_limit <= 0.0 || predicted->chi2 <= chi2_limit);
  }
  return later;
}

// Adds the confirmed closures' edges and solves the graph, unless the solve can wait. The agreeing
// scans of a batch were matched on one stretch of old nodes, one after the other: they share that
// local map's error, so together they are one measurement: each carries 1/n of its information,
// in the solve and in the χ² test after it.
void LoopCloser::Solve(ClosureAttempt& attempt) {
  BeforeBatch before{{}, {}, 0, 0, odometry_model_, taught_.size()};
  if (options_.odometry_edges) LearnOdometry(pending_.back());
  for (PoseGraphEdge& pending : pending_)
    pending.information /= static_cast<double>(pending_.size());
  const std::size_t batch = pending_.size();
  attempt.solve_deferred = SolveLater(attempt);
  for (const PoseGraphEdge& pending : pending_) {
    graph_.AddEdge(pending);
    unsolved_from_ = std::min(unsolved_from_, pending.from);
  }
  pending_.clear();
  if (attempt.solve_deferred) {
    unsolved_ = true;
    attempt.accepted = true;
    attempt.reason = "accepted";
    return;
  }
  before.first = graph_.edges().size() - batch;
  before.hold = unsolved_from_;
  before.nodes = graph_.nodes();
  for (const PoseGraphEdge& edge : graph_.edges()) before.active.push_back(edge.active);
  PoseGraphSummary summary = SolveGraph(attempt.largest_shift_m, before.hold);
  if (options_.set_aside_whole_batch && BatchSetAside(before.first))
    summary = SolveAgain(attempt, before);
  attempt.solve_iterations = summary.iterations;
  attempt.accepted = graph_.edges().back().active;
  attempt.reason = attempt.accepted ? "accepted" : "set aside by the graph";
  attempt.rendered = attempt.largest_shift_m > options_.render_min_shift_m;
}

// The solve set aside part of the batch. When the batch taught the odometry model and its closure
// misses the odometry chain by more than the matched one, and by more than a closure errs (the
// batch's own agreement, agree_m), the odometry its lesson trusted (one closure cannot disprove
// it) may be what bent the graph away from the batch (Fr079 seen over 120°, scan 997: the
// odometry chain 2.2 m and 0.66 rad off the closure, the matched chain 0.1 m): the graph is
// solved again from where it stood, the batch in and its lesson unlearned. A batch set aside
// otherwise, or again, is set aside whole, its lesson kept (edmonton with perfect odometry, seen
// over 120°: the odometry chain 2 cm off the closure, the matched chain 15 cm; with a laser 1 cm
// noisier: 5 cm and 4 cm), and the graph solved without it.
PoseGraphSummary LoopCloser::SolveAgain(ClosureAttempt& attempt, const BeforeBatch& before) {
  const bool taught = taught_.size() > before.taught;
  if (taught && taught_.back().odometry_miss.head<2>().norm() >
                    std::max(options_.agree_m, taught_.back().matched_miss.head<2>().norm())) {
    const OdometryModel learned = odometry_model_;
    const ChainMisses lesson = taught_.back();
    Unlearn(before.model, before.taught);
    Restore(before, true);
    const PoseGraphSummary summary = SolveGraph(attempt.largest_shift_m, before.hold);
    if (!BatchSetAside(before.first)) return summary;
    odometry_model_ = learned;
    taught_.push_back(lesson);
    WeighOdometry();
  }
  Restore(before, false);
  return SolveGraph(attempt.largest_shift_m, before.hold);
}

bool LoopCloser::BatchSetAside(std::size_t first) const {
  for (std::size_t i = first; i < graph_.edges().size(); ++i)
    if (!graph_.edges()[i].active) return true;
  return false;
}

void LoopCloser::Restore(const BeforeBatch& before, bool batch_active) {
  for (std::size_t i = 0; i < before.nodes.size(); ++i) graph_.SetNode(i, before.nodes[i]);
  for (std::size_t i = 0; i < graph_.edges().size(); ++i) {
    const PoseGraphEdge& edge = graph_.edges()[i];
    if (i >= before.first || edge.kind == EdgeKind::kClosure)
      graph_.SetInformation(i, edge.information,
                            i < before.first ? before.active[i] : batch_active);
  }
}

// The odometry model as it was before the batch taught it, its edges weighed again (none holds
// the graph while nothing is learned).
void LoopCloser::Unlearn(const OdometryModel& model, std::size_t taught) {
  odometry_model_ = model;
  taught_.resize(taught);
  if (odometry_model_.learned()) return WeighOdometry();
  for (const Node& node : nodes_)
    if (node.odometry_edge)
      graph_.SetInformation(*node.odometry_edge, graph_.edges()[*node.odometry_edge].information,
                            false);
}

// Solves the graph, the nodes before `hold_before` held (all free with 0); `largest_shift_m`
// becomes the largest node displacement it made.
PoseGraphSummary LoopCloser::SolveGraph(double& largest_shift_m, std::size_t hold_before) {
  unsolved_ = false;
  unsolved_from_ = kNoNode;
  partly_solved_ = hold_before > 0;
  reweighed_ = reweighed_ && hold_before > 0;
  local_map_.reset();  // the solve moves the nodes it was rendered from
  const std::vector<Pose2D> before = graph_.nodes();
  const PoseGraphSummary summary = graph_.Optimise(options_.graph, hold_before);
  largest_shift_m = 0.0;
  for (std::size_t i = 0; i < before.size(); ++i)
    largest_shift_m = std::max(largest_shift_m, Distance(before[i], graph_.nodes()[i]));
  return summary;
}

// The final solve, of the whole graph, when closures joined it unsolved or the solves since the
// last whole one held the older nodes.
bool LoopCloser::Finish() {
  if (!unsolved_ && !partly_solved_ && !reweighed_) return false;
  double largest_shift_m = 0.0;
  SolveGraph(largest_shift_m, 0);
  return largest_shift_m > options_.render_min_shift_m;
}

// Where node i's neighbour j puts it by the odometry (nothing without odometry at either).
std::optional<Pose2D> LoopCloser::NeighbourStart(std::size_t i, std::size_t j) const {
  if (j >= nodes_.size() || !nodes_[i].odometry || !nodes_[j].odometry) return std::nullopt;
  return graph_.nodes()[j] * Between(*nodes_[j].odometry, *nodes_[i].odometry);
}

// Where node i's neighbours put it by the odometry, when both put its heading farther from its
// own than `bound_rad`: a node whose match settled on another heading than both its neighbours'.
std::vector<Pose2D> LoopCloser::NeighbourStarts(std::size_t i, double bound_rad) const {
  const std::optional<Pose2D> before = i > 0 ? NeighbourStart(i, i - 1) : std::nullopt;
  const std::optional<Pose2D> after = NeighbourStart(i, i + 1);
  if (!before || !after) return {};
  const double own = graph_.nodes()[i].yaw_rad;
  if (std::abs(NormalizeAngle(before->yaw_rad - own)) <= bound_rad ||
      std::abs(NormalizeAngle(after->yaw_rad - own)) <= bound_rad)
    return {};
  return {*before, *after};
}

// The bound beyond which a node's heading stands out from its neighbours': k robust standard
// deviations (1.4826 × the median absolute) of every node's heading from where the node before
// puts it by the odometry.
double LoopCloser::NeighbourHeadingBound(double k) const {
  std::vector<double> misses;
  for (std::size_t i = 1; i < nodes_.size(); ++i)
    if (const std::optional<Pose2D> start = NeighbourStart(i, i - 1))
      misses.push_back(std::abs(NormalizeAngle(start->yaw_rad - graph_.nodes()[i].yaw_rad)));
  if (misses.empty()) return HUGE_VAL;
  const auto middle = misses.begin() + static_cast<std::ptrdiff_t>(misses.size() / 2);
  std::nth_element(misses.begin(), middle, misses.end());
  return k * 1.4826 * *middle;
}

FinalMatchSummary LoopCloser::MatchOnFinalMap(const MapView& map,
                                              const LocalisationOptions& localisation) {
  std::vector<NodeScan> scans;
  scans.reserve(nodes_.size());
  const double sigmas = options_.final_match.neighbour_sigmas;
  const double bound_rad = sigmas > 0.0 ? NeighbourHeadingBound(sigmas) : HUGE_VAL;
  for (std::size_t i = 0; i < nodes_.size(); ++i) {
    scans.push_back({i, &nodes_[i].scan, nodes_[i].path_m, {}});
    if (sigmas > 0.0) scans.back().other_starts = NeighbourStarts(i, bound_rad);
  }
  local_map_.reset();  // the solve moves the nodes it was rendered from
  return MatchNodesOnFinalMap(map, scans, mounting_, localisation, options_.final_match,
                              options_.sigma_floor_m, options_.sigma_floor_rad, options_.graph,
                              graph_);
}

std::optional<ChainMisses> LoopCloser::Chains(std::size_t a, std::size_t b,
                                              const std::optional<Pose2D>& closure) const {
  ChainMisses misses;
  misses.path_m = nodes_[b].path_m - nodes_[a].path_m;
  misses.start_path_m = nodes_[a].path_m;
  CompoundedPosture matched, position, heading, floor;
  for (std::size_t k = a + 1; k <= b; ++k) {
    if (!nodes_[k - 1].odometry || !nodes_[k].odometry) return std::nullopt;
    const PoseGraphEdge& sequential = graph_.edges()[nodes_[k].sequential_edge];
    matched.Append(sequential.T_from_to, nodes_[k].sequential_covariance);
    const Pose2D step = Between(*nodes_[k - 1].odometry, *nodes_[k].odometry);
    const OdometryStepShape shape = odometry_model_.Shape(step);
    position.Append(step, shape.position);
    heading.Append(step, shape.heading);
    floor.Append(step, shape.floor);
  }
  auto miss = [](const Pose2D& measured, const Pose2D& chain) {
    return Eigen::Vector3d(measured.x_m - chain.x_m, measured.y_m - chain.y_m,
                           NormalizeAngle(measured.yaw_rad - chain.yaw_rad));
  };
  const Pose2D& odometry = position.T_start_end;
  misses.matched_miss = closure ? miss(*closure, matched.T_start_end) : Eigen::Vector3d::Zero();
  misses.odometry_miss = miss(closure ? *closure : matched.T_start_end, odometry);
  misses.matched_covariance = matched.covariance;
  misses.odometry_per_position = position.covariance;
  misses.odometry_per_heading = heading.covariance;
  misses.odometry_floor = floor.covariance;
  misses.translation_m = (closure ? *closure : matched.T_start_end).Translation();
  return misses;
}

void LoopCloser::LearnOdometry(const PoseGraphEdge& closure) {
  // The closure measures `to` seen from `from`; the chains run from the older node.
  const std::optional<ChainMisses> misses =
      closure.from < closure.to ? Chains(closure.from, closure.to, closure.T_from_to)
                                : Chains(closure.to, closure.from, closure.T_from_to.Inverse());
  if (!misses) return;  // a node between them has no odometry
  taught_.push_back(*misses);
  const Eigen::Matrix3d covariance = closure.information.inverse();
  taught_.back().closure_covariance = 0.5 * (covariance + covariance.transpose());
  ExtendStretches();
  const std::size_t first = taught_.size() - std::min(taught_.size(), kMaxTaught);
  std::vector<ChainMisses> stretches;
  stretches.reserve(stretches_.size());
  for (const Stretch& stretch : stretches_) stretches.push_back(stretch.misses);
  odometry_model_.Learn({taught_.begin() + static_cast<std::ptrdiff_t>(first), taught_.end()},
                        std::move(stretches));
  WeighOdometry();
}

void LoopCloser::ExtendStretches() {
  for (std::size_t level = 0; level < kStretchLengths; ++level) {
    const double length_m = options_.odometry.stretch_m * static_cast<double>(1u << level);
    std::size_t& start = stretch_starts_[level];
    for (std::size_t k = start + 1; k < nodes_.size(); ++k) {
      if (!nodes_[k - 1].odometry || !nodes_[k].odometry) {
        start = k;
        continue;
      }
      if (nodes_[k].path_m - nodes_[start].path_m < length_m || k - start < 2) continue;
      stretches_.push_back({nodes_[start].path_m, *Chains(start, k, std::nullopt)});
      start = k;
    }
  }
  const double longest_m =
      options_.odometry.stretch_m * static_cast<double>(1u << (kStretchLengths - 1));
  const double window_start_m = path_m() - kStretchWindow * longest_m;
  stretches_.erase(
      std::remove_if(stretches_.begin(), stretches_.end(),
                     [&](const Stretch& s) { return s.start_path_m < window_start_m; }),
      stretches_.end());
}

void LoopCloser::WeighOdometry(std::size_t first_node) {
  for (std::size_t k = std::max<std::size_t>(first_node, 1); k < nodes_.size(); ++k) {
    Node& node = nodes_[k];
    if (!nodes_[k - 1].odometry || !node.odometry) continue;
    const Pose2D step = Between(*nodes_[k - 1].odometry, *node.odometry);
    const Eigen::Matrix3d covariance = odometry_model_.StepCovariance(step);
    Eigen::Matrix3d information = covariance.inverse();
    information = 0.5 * (information + information.transpose());
    const bool active = OdometryHoldsHeading(covariance, node.sequential_covariance);
    if (node.odometry_edge) {
      const PoseGraphEdge& edge = graph_.edges()[*node.odometry_edge];
      if (edge.active || active) reweighed_ = true;
      graph_.SetInformation(*node.odometry_edge, information, active);
    } else if (active) {
      node.odometry_edge = graph_.edges().size();
      graph_.AddEdge({k - 1, k, step, information, EdgeKind::kOdometry});
      reweighed_ = true;
    }
  }
}

void LoopCloser::SetPriorMap(const PointMap& map) {
  prior_ = {};
  for (std::size_t i = 0; i < map.size(); ++i) {
    if (!map.alive(i)) continue;
    prior_.points.push_back(map.point(i));
    prior_.normals.push_back(map.normal(i));
    prior_.spacings_m.push_back(map.spacing(i));
  }
}

PointMap LoopCloser::Render(const PointMapOptions& map_options,
                            const MapExtensionOptions& extension, std::size_t first_node,
                            bool final) const {
  PointMap map(map_options);
  map.Restore(prior_.points, prior_.spacings_m, prior_.normals);
  std::vector<std::uint32_t> laid_after(nodes_.size(), 0);  // the map's size after each node
  for (std::size_t i = first_node; i < nodes_.size(); ++i) {
    ExtendMap(map, nodes_[i].scan, mounting_.LaserPose(graph_.nodes()[i]), extension);
    laid_after[i] = static_cast<std::uint32_t>(map.size());
  }
  if (!final || !extension.carve_with_earlier_scans || !(extension.free_space_margin_m > 0.0))
    return map;
  for (std::size_t i = first_node; i + 1 < nodes_.size(); ++i)
    map.CarveFreeSpace(nodes_[i].scan, mounting_.LaserPose(graph_.nodes()[i]),
                       extension.free_space_margin_m, extension.free_space_margin_per_m,
                       laid_after[i]);
  return map;
}

std::size_t LoopCloser::FirstNewestNode(double within_m, std::size_t count) const {
  std::size_t first = nodes_.size() - std::min(count, nodes_.size());
  while (first > 0 && path_m() - nodes_[first - 1].path_m <= within_m) --first;
  return first;
}

std::optional<Pose2D> LoopCloser::NewestNode() const {
  if (graph_.nodes().empty()) return std::nullopt;
  return graph_.nodes().back();
}

// An unconfirmed scan follows the odometry from its node where the odometry holds the heading of
// that motion (as an odometry edge must to join the graph).
bool LoopCloser::ByOdometry(const Anchoring& anchor) const {
  if (!anchor.T_node_robot_odometry || !odometry_model_.learned() || anchor.node == 0) return false;
  return OdometryHoldsHeading(odometry_model_.StepCovariance(*anchor.T_node_robot_odometry),
                              nodes_[anchor.node].sequential_covariance);
}

std::vector<std::optional<Pose2D>> LoopCloser::CorrectedPostures() const {
  std::vector<std::optional<Pose2D>> postures(anchors_.size());
  for (std::size_t i = 0; i < anchors_.size(); ++i) {
    if (!anchors_[i]) continue;
    postures[i] = graph_.nodes()[anchors_[i]->node] * (ByOdometry(*anchors_[i])
                                                           ? *anchors_[i]->T_node_robot_odometry
                                                           : anchors_[i]->T_node_robot);
  }
  SpreadSkippedCorrections(postures);
  return postures;
}

void LoopCloser::SpreadSkippedCorrections(std::vector<std::optional<Pose2D>>& postures) const {
  for (std::size_t b = 1; b < anchors_.size(); ++b) {
    const std::optional<Anchoring>& last = anchors_[b];
    if (!last || !last->prediction_node) continue;
    // One that kept its prediction made no correction: its run goes on to the next scan.
    if (SharesNextCorrection(b)) continue;
    std::size_t first = b;  // the run of skipped (or unconfirmed) scans before b
    while (first > 0 && SharesNextCorrection(first - 1)) --first;
    const std::size_t a = first - 1;  // the localised scan before them
    if (first == b || first == 0 || !anchors_[a] || !anchors_[a]->timing) continue;
    if (ByOdometry(*anchors_[a])) continue;  // not the posture the run was carried from
    const Pose2D predicted = graph_.nodes()[*last->prediction_node] * last->T_node_prediction;
    const Pose2D& localised = *postures[b];
    const Eigen::Vector3d correction(localised.x_m - predicted.x_m, localised.y_m - predicted.y_m,
                                     NormalizeAngle(localised.yaw_rad - predicted.yaw_rad));
    const double t_a = anchors_[a]->timing->timestamp_s, t_b = last->timing->timestamp_s;
    for (std::size_t k = first; k < b; ++k) {
      const double share =
          t_b > t_a ? std::clamp((anchors_[k]->timing->timestamp_s - t_a) / (t_b - t_a), 0.0, 1.0)
                    : static_cast<double>(k - a) / static_cast<double>(b - a);
      const Pose2D& skipped = *postures[k];
      postures[k] =
          Pose2D(skipped.x_m + share * correction.x(), skipped.y_m + share * correction.y(),
                 NormalizeAngle(skipped.yaw_rad + share * correction.z()));
    }
  }
}

}  // namespace scanloc
