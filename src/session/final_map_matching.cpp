#include "scanloc/session/final_map_matching.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "scanloc/graph/relative_covariance.hpp"

namespace scanloc {
namespace {

// The node's posture in the world as its scan matched on the map, with the edge's information;
// nothing when the rules did not validate it or the refinement does not pin it. The refinement
// starts from the graph's posture, which the map was rendered from: only the refined posture is
// judged (rules 1 and 2; rule 3 has nothing to compare it with).
std::optional<PoseGraphEdge> MatchNode(const MapView& map, const NodeScan& node,
                                       const Pose2D& T_world_robot, const LaserMounting& mounting,
                                       const LocalisationOptions& localisation,
                                       double sigma_floor_m, double sigma_floor_rad) {
  RefinerOptions refiner = localisation.refiner;
  refiner.ceres.score_initial = false;
  const RefinementResult refined =
      Refine(map, *node.scan, mounting.LaserPose(T_world_robot), localisation.scoring,
             localisation.validation.alpha_m, refiner);
  const CandidateRanking ranking = RankCandidates({refined.test_after}, localisation.validation);
  if (ranking.candidates.front().verdict != Verdict::kValid || !refined.has_covariance ||
      refined.degenerate)
    return std::nullopt;
  PoseGraphEdge edge;
  edge.to = node.node;
  edge.T_from_to = mounting.RobotPose(refined.T_world_laser);
  edge.information = EdgeInformation(refined.covariance, 0.0, sigma_floor_m, sigma_floor_rad);
  edge.kind = EdgeKind::kSequential;  // trusted as measured, as the chain's own steps
  return edge;
}

}  // namespace

void FinalMatchOptions::Validate() const {
  if (!(spacing_m >= 0.0) || !std::isfinite(spacing_m))
    throw std::invalid_argument("loop_closure.final_match_spacing_m must be finite and >= 0");
}

FinalMatchSummary MatchNodesOnFinalMap(const MapView& map, const std::vector<NodeScan>& nodes,
                                       const LaserMounting& mounting,
                                       const LocalisationOptions& localisation,
                                       const FinalMatchOptions& options, double sigma_floor_m,
                                       double sigma_floor_rad, PoseGraphOptions graph_options,
                                       PoseGraph& graph) {
  const auto start = std::chrono::steady_clock::now();
  FinalMatchSummary summary;
  PoseGraph solved = graph;
  const std::size_t world = solved.AddNode(Pose2D());
  bool first = true;
  double last_path_m = 0.0;
  for (const NodeScan& node : nodes) {
    if (!first && node.path_m - last_path_m < options.spacing_m) continue;
    first = false;
    last_path_m = node.path_m;
    ++summary.matched;
    std::optional<PoseGraphEdge> edge = MatchNode(map, node, graph.nodes()[node.node], mounting,
                                                  localisation, sigma_floor_m, sigma_floor_rad);
    if (!edge) continue;
    edge->from = world;
    solved.AddEdge(*edge);
    ++summary.joined;
  }
  if (summary.joined > 0) {
    graph_options.fixed_node = world;
    // The closures were judged as they joined and at the run's end: they keep that judgement
    // (their loss still bounds their pull), and one solve suffices.
    graph_options.closure_rejection_chi2 = 0.0;
    summary.solve_iterations = solved.Optimise(graph_options).iterations;
    for (std::size_t i = 0; i < graph.nodes().size(); ++i) {
      summary.largest_shift_m =
          std::max(summary.largest_shift_m,
                   (solved.nodes()[i].Translation() - graph.nodes()[i].Translation()).norm());
      graph.SetNode(i, solved.nodes()[i]);
    }
  }
  summary.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return summary;
}

}  // namespace scanloc
