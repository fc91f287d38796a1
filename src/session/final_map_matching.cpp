#include "scanloc/session/final_map_matching.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <optional>
#include <stdexcept>

#include "scanloc/graph/relative_covariance.hpp"

namespace scanloc {
namespace {

// The best ranked refinement of `starts` that the rules validate (1–3, then ranked by 4 and 5);
// -1 when none is, or when the best does not pin the posture.
int BestMatch(const MapView& map, const NodeScan& node, const std::vector<Pose2D>& starts,
              const LaserMounting& mounting, const LocalisationOptions& localisation,
              std::vector<RefinementResult>& refined) {
  RefinerOptions refiner = localisation.refiner;
  refiner.ceres.score_initial = false;
  std::vector<LikelihoodTestResult> tests;
  for (const Pose2D& start : starts) {
    refined.push_back(Refine(map, *node.scan, mounting.LaserPose(start), localisation.scoring,
                             localisation.validation.alpha_m, refiner));
    tests.push_back(refined.back().test_after);
  }
  const CandidateRanking ranking = RankCandidates(tests, localisation.validation);
  if (ranking.best < 0) return -1;
  const RefinementResult& best = refined[static_cast<std::size_t>(ranking.best)];
  return best.has_covariance && !best.degenerate ? ranking.best : -1;
}

// The node's posture in the world as its scan matched on the map, with the edge's information;
// nothing when the rules did not validate it or the refinement does not pin it. The refinement
// starts from the graph's posture, which the map was rendered from, and from the other starts
// given, all judged and ranked as candidates are.
std::optional<PoseGraphEdge> MatchNode(const MapView& map, const NodeScan& node,
                                       const Pose2D& T_world_robot, const LaserMounting& mounting,
                                       const LocalisationOptions& localisation,
                                       double sigma_floor_m, double sigma_floor_rad,
                                       bool& from_other_start) {
  std::vector<Pose2D> starts{T_world_robot};
  starts.insert(starts.end(), node.other_starts.begin(), node.other_starts.end());
  std::vector<RefinementResult> refined;
  const int best = BestMatch(map, node, starts, mounting, localisation, refined);
  if (best < 0) return std::nullopt;
  from_other_start = best > 0;
  const RefinementResult& match = refined[static_cast<std::size_t>(best)];
  PoseGraphEdge edge;
  edge.to = node.node;
  edge.T_from_to = mounting.RobotPose(match.T_world_laser);
  edge.information = EdgeInformation(match.covariance, 0.0, sigma_floor_m, sigma_floor_rad);
  edge.kind = EdgeKind::kSequential;  // trusted as measured, as the chain's own steps
  return edge;
}

}  // namespace

void FinalMatchOptions::Validate() const {
  if (!(spacing_m >= 0.0) || !std::isfinite(spacing_m))
    throw std::invalid_argument("loop_closure.final_match_spacing_m must be finite and >= 0");
  if (!(neighbour_sigmas >= 0.0) || !std::isfinite(neighbour_sigmas))
    throw std::invalid_argument(
        "loop_closure.final_match_neighbour_sigmas must be finite and >= 0");
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
    bool from_other_start = false;
    std::optional<PoseGraphEdge> edge =
        MatchNode(map, node, graph.nodes()[node.node], mounting, localisation, sigma_floor_m,
                  sigma_floor_rad, from_other_start);
    if (!node.other_starts.empty()) ++summary.from_neighbours;
    if (!edge) continue;
    if (from_other_start) ++summary.took_neighbours;
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
