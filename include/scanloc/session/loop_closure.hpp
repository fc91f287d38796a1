#pragma once
// Loop closure (issue 16): the scans that extend the map become nodes of a pose graph, each
// keeping its scan, so that the map can be rendered again from corrected postures. Consecutive
// nodes are linked by the postures the session gave them, weighted by the refinement's
// covariance; when the session comes back near nodes laid a long path ago, the scan is localised
// against a map rendered from those old nodes only, over a window that grows with the path driven
// since, and a posture the Likelihood Test validates (and that the geometry pins in every
// direction) becomes a closure edge. The graph is then solved; closures it cannot explain are set
// aside (PoseGraph), and every scan's posture follows its node.

#include <array>
#include <cstddef>
#include <optional>
#include <string>
#include <vector>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/graph/odometry_model.hpp"
#include "scanloc/graph/pose_graph.hpp"
#include "scanloc/maps/point_map.hpp"
#include "scanloc/session/final_map_matching.hpp"
#include "scanloc/session/localisation.hpp"
#include "scanloc/session/map_extension.hpp"
#include "scanloc/session/wide_search.hpp"

namespace scanloc {

struct LoopClosureOptions {
  // On by default (issue 16); off, the session tracks against the whole map it built, as before.
  bool enabled = true;
  // A node may close a loop with the current scan once the path driven since it was laid exceeds
  // this: younger nodes are the map the session is matching against anyway.
  double min_path_m = 10.0;
  // The map a closure is matched on: the nearest old node within local_map_radius_m of the
  // current posture and the nodes laid just before and after it, one stretch of one pass, at most
  // max_local_nodes (enough walls to pin a posture, a bounded cost), each within the radius too;
  // fewer than min_local_nodes try nothing.
  double local_map_radius_m = 5.0;
  int min_local_nodes = 3;
  int max_local_nodes = 30;
  // A closure is tried once this many new nodes were laid and this much path driven since the
  // last attempt: the cost stays bounded per node and per metre driven, however densely a log
  // lays its nodes (every 0.1 m on the Kümmerle logs, every 0.9 m on the Radish logs).
  int attempt_every_nodes = 5;
  double attempt_every_m = 2.0;
  // The window searched around the current posture: min_half_width_m + translation_error_per_m ·
  // the path driven since the nearest old node, at most max_half_width_m; the same for heading.
  // With window_sigmas > 0 it follows the graph instead: window_sigmas standard deviations of the
  // current node's posture relative to the old node (RelativeCovariance: the chain's edges and
  // the closures since), at least the minima; a window that would need more than the maxima is
  // not searched (a look-alike inside it could not be told from the place outside).
  double min_half_width_m = 0.3;
  double translation_error_per_m = 0.02;
  double max_half_width_m = 2.0;
  double min_half_yaw_rad = 0.1;
  double heading_error_per_m = 0.005;
  double max_half_yaw_rad = 0.5;
  double window_sigmas = 0.0;
  WideSearchOptions search;
  // The refinement of an accepted closure pins the posture to within this (its largest standard
  // deviation) and is not flagged degenerate: a corridor gives no closure along its axis. Another
  // valid refinement farther than distinct_m or distinct_rad from it makes the match ambiguous.
  double max_sigma_m = 0.05;
  double distinct_m = 0.3;
  double distinct_rad = 0.1;
  // A closure is confirmed when this many consecutive nodes match the old nodes with the same
  // correction (within agree_m and agree_rad of each other); while one is pending, every new node
  // is tried. One scan that fits a look-alike place does not bend the map.
  int confirm_after = 5;
  double agree_m = 0.1;
  double agree_rad = 0.03;
  // The scans between a run's first and its last search only the smallest window (the minima
  // above) around where the run puts them: its correction applied to the session's posture, with
  // the previous scan's match moved on by the odometry as a second start. What they add to the
  // run is agreement (a validated match farther than agree_m or agree_rad from the run's starts
  // another, as any does). The last scan, like the first, searches the whole window, so that a
  // look-alike inside it still makes the run ambiguous before it is applied. Off by default: it
  // takes 8 % of Intel's CPU off, but on ACES it keeps fewer closures and the maps it makes mislead
  // `scanloc localise` (docs/BENCHMARKS.md, 2026-12-07).
  bool confirm_from_run = false;
  // Floors added to the refinement's standard deviations (it knows only the scan's own noise, not
  // the map's): the edges' information is that of σ ⊕ floor.
  double sigma_floor_m = 0.005;
  double sigma_floor_rad = 0.001;
  PoseGraphOptions graph;
  // A batch of agreeing closures is one measurement. When the solve that takes it in sets aside
  // any of its edges (χ² beyond graph.closure_rejection_chi2), the graph is solved again from where
  // it stood before the batch: first, when the batch taught the odometry model and its closure
  // misses the odometry chain by more than the matched chain and agree_m, with the batch and
  // without that lesson (the odometry it trusted may be what bent the graph away from the batch);
  // otherwise, or when the batch is set aside again, without the batch, its lesson kept. The solve
  // that set it aside no longer leaves its bend in the map (Fr079 seen over 120°: 2 m and 36° at
  // scan 997, docs/BENCHMARKS.md, "Unvalidated corrections, and a batch its own lesson bent away").
  bool set_aside_whole_batch = true;
  // Consecutive nodes are linked by their odometry too, once a closure has shown how good it is
  // (OdometryModel): each confirmed closure teaches the model, and every odometry edge is weighed
  // again before the solve.
  bool odometry_edges = true;
  OdometryModelOptions odometry;
  // After a solve the map is rendered again from the nodes when one of them moved more than this.
  // A confirmed closure predicted to move its node by less (the first-order correction: the
  // chain's covariance weighed against the closure's) and that the graph can explain (χ² within
  // graph.closure_rejection_chi2) joins the graph unsolved: the next larger closure's solve, or
  // Finish, takes it in.
  double render_min_shift_m = 0.02;
  // The map the session tracks against: every node (tracking_path_m 0), or only the newest nodes:
  // those laid within tracking_path_m of path from the newest one, and at least the newest
  // tracking_min_nodes (a sparse log lays fewer nodes per metre). It is rendered again once it
  // holds twice that. Old places then come back only through closures, which the graph spreads
  // over the loop, instead of the tracker snapping onto their walls.
  double tracking_path_m = 10.0;
  int tracking_min_nodes = 0;
  // In the corrected trajectory, the scans before a localised one that were skipped take a share
  // of the correction it made to its prediction (CorrectedPostures); with this, so do the
  // unconfirmed scans that kept the prediction, back to the last scan that did not: they were
  // carried by the same odometry and erred alike. Not those that follow the odometry from their
  // node (the odometry model trusts it more than the match that would correct it).
  bool spread_over_unconfirmed = true;
  // A heading correction the tracker made beyond this fraction of the correction gate's heading
  // bound is withdrawn when the closure tried at the same scan disputes it (turn_dispute.hpp): the
  // scan takes the prediction. 0 turns this off.
  double dispute_turn_of_bound = 0.75;
  // At the end of the run, the nodes matched once more on the whole map (final_map_matching.hpp).
  FinalMatchOptions final_match;
  // Throws std::invalid_argument naming the first option out of its domain.
  void Validate() const;
};

// One closure tried: where, against what, what the Likelihood Test said, and what it changed.
struct ClosureAttempt {
  std::size_t iteration = 0;      // the scan's record index
  std::size_t node = 0;           // the current node
  std::size_t old_node = 0;       // the old node the edge starts from (the nearest)
  std::size_t old_iteration = 0;  // its scan's record index
  std::size_t local_nodes = 0;
  double path_since_m = 0.0;  // path driven since the old node
  // The current node's standard deviation relative to the old node, from the graph: the largest
  // of its position (m) and of its heading (rad).
  double chain_sigma_m = 0.0;
  double chain_sigma_rad = 0.0;
  SearchWindow window;
  // A run's middle scan: `window` is the smallest, around where the pending run puts the scan.
  bool from_run = false;
  bool accepted = false;  // validated, pinned, and kept by the graph
  bool pending = false;   // validated and pinned, waiting for agreeing scans
  // The correction the closures pending before this one agreed on (the old nodes' frame seen from
  // the session's), when some were.
  std::optional<Pose2D> run_correction;
  std::string reason;            // why not, or "accepted"
  Pose2D T_world_robot_before;   // the session's posture of the scan
  Pose2D T_world_robot_matched;  // against the old nodes (when something was refined)
  Pose2D T_old_robot;            // the same seen from the old node: the closure's measurement
  std::optional<LikelihoodTestResult> test;  // of the kept refinement
  // The largest node shift the closures confirmed here would bring, predicted before solving, m,
  // and whether the solve was left for later because it is small.
  double predicted_shift_m = 0.0;
  bool solve_deferred = false;
  double largest_shift_m = 0.0;  // the solve's largest node displacement
  int solve_iterations = 0;      // the solve's iterations, over all its rounds (0: no solve)
  bool rendered = false;         // the map was rendered again
  double time_s = 0.0;
};

// When a record's scan was taken, whether it was skipped, and the prediction it started from.
struct AnchorTiming {
  double timestamp_s = 0.0;
  bool skipped = false;
  Pose2D prediction;  // T_world_robot: the last posture moved by the odometry
};

class LoopCloser {
 public:
  LoopCloser(const LoopClosureOptions& options, const LaserMounting& mounting);

  // The scan of record `iteration` extended the map at T_world_robot: it becomes a node, linked
  // to the previous one with `laser_covariance` (of its refinement, or empty when it has none),
  // and by the odometry (the robot's odometry pose at the scan, when the log has one) once the
  // odometry model has learned from a closure.
  void AddNode(std::size_t iteration, const LaserScan& scan, const Pose2D& T_world_robot,
               const std::optional<Eigen::Matrix3d>& laser_covariance,
               const std::optional<Pose2D>& odometry = std::nullopt);
  // Every record's posture, remembered relative to the newest node (call after AddNode). A scan
  // the Likelihood Test did not confirm also remembers its odometry relative to the node's: where
  // the odometry model says the odometry knows the motion from the node at least as well as a
  // matched step knows its own, the corrected posture follows the odometry, which the scan could
  // not disprove, rather than an unconfirmed match.
  // With `timing`, a scan that was skipped (not localised: it kept the odometry's prediction)
  // also takes a share of the correction the next localised scan made to its own prediction
  // (CorrectedPostures); with spread_over_unconfirmed, an unconfirmed scan that kept its
  // prediction does too.
  void Anchor(std::size_t iteration, const Pose2D& T_world_robot, bool confirmed = true,
              const std::optional<Pose2D>& odometry = std::nullopt,
              const std::optional<AnchorTiming>& timing = std::nullopt);
  // Tries a closure for the newest node when one is due. On an accepted one, the graph is solved
  // and the caller renders the map again when the attempt says so.
  std::optional<ClosureAttempt> MaybeClose(const LocalisationOptions& localisation,
                                           const PointMapOptions& map_options);
  // Solves the graph when closures joined it unsolved; true when that moved a node more than
  // render_min_shift_m (the map is then worth rendering again).
  bool Finish();
  // The final map matching (final_map_matching.hpp) of the nodes on `map`, the whole map rendered
  // from them after Finish: the nodes move to the graph solved with the matches.
  FinalMatchSummary MatchOnFinalMap(const MapView& map, const LocalisationOptions& localisation);

  // A saved map the session started on: every render starts from its live points, restored as
  // they were (the nodes' scans then carve and extend it as the session did). None by default.
  void SetPriorMap(const PointMap& map);
  // The map rendered from the nodes from `first_node` on (every node by default) at their current
  // postures, over the prior map, carving as the session does. With `final` and the extension's
  // carve_with_earlier_scans, each node's scan then carves the points the later nodes laid.
  PointMap Render(const PointMapOptions& map_options, const MapExtensionOptions& extension,
                  std::size_t first_node = 0, bool final = false) const;
  // The first of the newest nodes: those that lie within `within_m` of path from the newest one,
  // and at least the newest `count` (0 without nodes).
  std::size_t FirstNewestNode(double within_m, std::size_t count) const;
  // The path driven from the first node to the newest one (0 without nodes), m.
  double path_m() const { return nodes_.empty() ? 0.0 : nodes_.back().path_m; }
  // The newest node's posture (after a solve it moves).
  std::optional<Pose2D> NewestNode() const;
  // Moves the newest node (a withdrawn correction), its edge from the node before with it.
  void MoveNewestNode(const Pose2D& T_world_robot);
  // Each anchored record's posture following its node, by record index (none before the first
  // node). A run of skipped scans between two localised ones (anchored with timings) takes a
  // share of the correction the second made to its own prediction: the odometry that carried the
  // skipped scans erred until the second as it did there (its drift, the scans' latency). The
  // share grows with the time since the first (with the count of scans when time stands still
  // or goes back).
  std::vector<std::optional<Pose2D>> CorrectedPostures() const;

  const PoseGraph& graph() const { return graph_; }
  const OdometryModel& odometry_model() const { return odometry_model_; }
  const std::vector<ClosureAttempt>& attempts() const { return attempts_; }
  const LoopClosureOptions& options() const { return options_; }

 private:
  struct Node {
    std::size_t iteration = 0;
    LaserScan scan;
    double path_m = 0.0;  // path driven from the first node to this one
    std::optional<Pose2D> odometry;
    std::size_t sequential_edge = 0;  // the edge from the previous node (none for the first)
    Eigen::Matrix3d sequential_covariance = Eigen::Matrix3d::Zero();  // that edge's, inverted once
    std::optional<std::size_t> odometry_edge;                         // the odometry's, beside it
  };
  struct Anchoring {
    std::size_t node = 0;
    Pose2D T_node_robot;
    std::optional<Pose2D> T_node_robot_odometry;  // of an unconfirmed scan
    std::optional<AnchorTiming> timing;
    // Unconfirmed, and its posture the prediction: on the odometry's chain from the last one.
    bool kept_prediction = false;
    // A localised scan after skipped ones: its prediction, from the node they are anchored to.
    std::optional<std::size_t> prediction_node;
    Pose2D T_node_prediction;
  };

  struct PriorPoints {
    std::vector<Eigen::Vector2d> points, normals;
    std::vector<double> spacings_m;
  };

  bool ByOdometry(const Anchoring& anchor) const;
  bool Skipped(std::size_t iteration) const;
  bool SharesNextCorrection(std::size_t iteration) const;
  std::optional<Pose2D> NeighbourStart(std::size_t i, std::size_t j) const;
  std::vector<Pose2D> NeighbourStarts(std::size_t i, double bound_rad) const;
  double NeighbourHeadingBound(double k) const;
  void SpreadSkippedCorrections(std::vector<std::optional<Pose2D>>& postures) const;
  std::vector<std::size_t> OldNodesNear(const Pose2D& T_world_robot, double path_m) const;
  std::optional<ClosureAttempt> Try(const LocalisationOptions& localisation,
                                    const PointMapOptions& map_options);
  std::vector<Candidate> RunCandidates(std::size_t newest) const;
  const PointMap& LocalMap(const std::vector<std::size_t>& old, const PointMapOptions& map_options);
  bool FitWindow(ClosureAttempt& attempt) const;
  void Judge(const LocalisationResult& result, ClosureAttempt& attempt);
  void Confirm(const Eigen::Matrix3d& covariance, ClosureAttempt& attempt);
  bool SolveLater(ClosureAttempt& attempt) const;
  void Solve(ClosureAttempt& attempt);
  PoseGraphSummary SolveGraph(double& largest_shift_m, std::size_t hold_before);
  // The graph and the odometry model as a batch of closures found them: its edges are those from
  // `first` on, solved with the nodes before `hold` held.
  struct BeforeBatch {
    std::vector<Pose2D> nodes;
    std::vector<bool> active;  // each edge's, the batch's included
    std::size_t first = 0, hold = 0;
    OdometryModel model;
    std::size_t taught = 0;
  };
  PoseGraphSummary SolveAgain(ClosureAttempt& attempt, const BeforeBatch& before);
  // Whether the solve set aside one of the edges from `first` on (the batch just added).
  bool BatchSetAside(std::size_t first) const;
  // The nodes and the closures' activity put back as they were before the batch, the batch's
  // edges active or not.
  void Restore(const BeforeBatch& before, bool batch_active);
  void Unlearn(const OdometryModel& model, std::size_t taught);
  // The odometry model taught by one more confirmed closure (when every node it spans has
  // odometry), and every odometry edge weighed again.
  void LearnOdometry(const PoseGraphEdge& closure);

  // The matched and the odometry chains from node a to node b (a < b), against `closure` (the
  // posture of b seen from a) when given; nothing when a node between them has no odometry.
  std::optional<ChainMisses> Chains(std::size_t a, std::size_t b,
                                    const std::optional<Pose2D>& closure) const;
  // The chain cut into stretches of odometry.stretch_m of path, and again into stretches twice,
  // four and eight times as long (the odometry chain against the matched chain over each): those
  // completed since the last call join stretches_, those now out of its window leave it.
  void ExtendStretches();
  // The odometry edges into the nodes from `first_node` on added, or weighed again, with the
  // model as it stands; when one that holds the graph was added or weighed, the next Finish
  // solves the whole graph.
  void WeighOdometry(std::size_t first_node = 1);

  LoopClosureOptions options_;
  LaserMounting mounting_;
  PoseGraph graph_;
  OdometryModel odometry_model_;
  std::vector<ChainMisses> taught_;  // of each closure the odometry model learned from
  struct Stretch {
    double start_path_m = 0.0;  // the path driven at its first node
    ChainMisses misses;
  };
  std::vector<Stretch> stretches_;  // completed within the newest kStretchWindow of path
  // Stretches of several lengths: the odometry's noise grows with the path, the matching's jitter
  // at a stretch's two ends does not, and only stretches of several lengths tell them apart.
  static constexpr std::size_t kStretchLengths = 4;
  // The node the stretch under way of each length starts at.
  std::array<std::size_t, kStretchLengths> stretch_starts_{};
  // The newest closures the model learns from: the cost of learning stays bounded per closure
  // however many a long session confirms, and the model follows an odometry that changes.
  static constexpr std::size_t kMaxTaught = 20;
  // The stretches the model learns from: those that start within the newest path as long as this
  // many stretches of the longest length, for the same reasons (without it, each closure's fit
  // would cost more the longer the session: the stretches grow with the path).
  static constexpr double kStretchWindow = 32.0;
  bool reweighed_ = false;  // active odometry edges added or weighed since the last whole solve
  std::vector<Node> nodes_;
  std::vector<std::optional<Anchoring>> anchors_;  // by record index
  std::vector<ClosureAttempt> attempts_;
  PriorPoints prior_;  // of the saved map the session started on, if any
  std::size_t nodes_since_attempt_ = 0;
  double path_at_attempt_m_ = 0.0;  // the newest node's path when the last attempt was due
  // Closures found but not yet confirmed: their edges and the correction they agree on.
  std::vector<PoseGraphEdge> pending_;
  Pose2D pending_correction_;
  bool unsolved_ = false;  // closures joined the graph since its last solve
  // The oldest node of the closures that joined the graph since its last solve: a solve holds
  // the nodes before it (the loop they close is what moves), and Finish solves the whole graph.
  static constexpr std::size_t kNoNode = static_cast<std::size_t>(-1);
  std::size_t unsolved_from_ = kNoNode;
  bool partly_solved_ = false;    // a solve held nodes since the last whole one
  LikelihoodField search_field_;  // the storage of every attempt's search field
  // The map of the latest attempt's old nodes, kept until a solve moves nodes: the next attempt
  // matched on the same stretch of old nodes, with the same options, uses it again.
  std::vector<std::size_t> local_nodes_;
  PointMapOptions local_map_options_;
  std::optional<PointMap> local_map_;
};

}  // namespace scanloc
