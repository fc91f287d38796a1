#pragma once
// The final map matching: at the end of a run, the nodes' scans matched once more on the whole map
// rendered from the solved graph, and the graph solved again with those matches in it.
//
// Why. The solved graph places each node by its chain of matched steps (and odometry steps) and
// by the closures confirmed along it. A place the robot passed several times holds walls laid by
// every pass; the map there is their consensus, and a node matched on it sees the other passes'
// walls as well as its own. Each validated match is the node's posture in the world, measured with
// the refinement's covariance (plus the graph's floors): it joins a copy of the graph as an edge
// from a world vertex held fixed (the gauge), beside the chain's edges, and one more solve spreads
// them. Where tight odometry edges hold the chain (a perfect odometry), a match that disagrees by
// the matching's own noise barely moves it; where the chain is the matching's own, the matches
// pull each node to the consensus, and the scans anchored to a node move with it.
//
// The matches share the map and one another's walls, so a node is matched once per spacing_m of
// path only: on a log that lays a node every 0.1 m, neighbours would match the same walls with the
// same error, and the cost stays proportional to the path, not to the node density. The graph the
// session keeps (and writes as graph.g2o) takes the solved postures; the matches themselves are not
// among its edges.

#include <cstddef>
#include <vector>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/graph/pose_graph.hpp"
#include "scanloc/session/localisation.hpp"
#include "scanloc/simulation/simulated_scan.hpp"

namespace scanloc {

struct FinalMatchOptions {
  // On by default; off, the trajectory and the map are the graph's as solved during the run.
  bool enabled = true;
  // One node matched per this much path (the first node, then the first one this far along the
  // path from the last one matched); 0 matches every node, m.
  double spacing_m = 0.5;
  // A node whose heading stands out from where both its neighbours put it by the odometry, by
  // more than this many robust standard deviations of every node's (from the one before), is
  // refined from those two postures too, and the best match the rules validate is kept; 0 (the
  // default): never. 3 halves acapulco's worst relation but moves ACES nodes on which the
  // localiser then confirms a corridor look-alike (docs/BENCHMARKS.md).
  double neighbour_sigmas = 0.0;
  // Throws std::invalid_argument naming the first option out of its domain.
  void Validate() const;
};

// A node's scan and where it lies along the path.
struct NodeScan {
  std::size_t node = 0;
  const LaserScan* scan = nullptr;
  double path_m = 0.0;
  // Other postures to refine from besides the node's own: where its neighbours put it by the
  // odometry (a node whose own match settled on a wrong heading, between neighbours that did not).
  std::vector<Pose2D> other_starts;
};

struct FinalMatchSummary {
  std::size_t matched = 0;          // nodes whose scans were matched on the map
  std::size_t joined = 0;           // of those, validated, pinned matches that joined the graph
  std::size_t from_neighbours = 0;  // matched from their neighbours' postures too
  std::size_t took_neighbours = 0;  // of those, joined with the match from a neighbour's posture
  int solve_iterations = 0;         // of the solve with them
  double largest_shift_m = 0.0;     // the largest node displacement the solve made
  double wall_s = 0.0;
};

// Matches the scans of `nodes` (in path order, spaced as the options say) on `map`, each from its
// node's posture in `graph` and from its other_starts (the best ranked of those refinements the
// rules validate is the node's match); the validated ones whose refinement has a covariance and
// is not degenerate join a copy of the graph as described above, and `graph`'s nodes take the
// solved postures (its edges stay as they were). Nothing is solved when no match joined.
FinalMatchSummary MatchNodesOnFinalMap(const MapView& map, const std::vector<NodeScan>& nodes,
                                       const LaserMounting& mounting,
                                       const LocalisationOptions& localisation,
                                       const FinalMatchOptions& options, double sigma_floor_m,
                                       double sigma_floor_rad, PoseGraphOptions graph_options,
                                       PoseGraph& graph);

}  // namespace scanloc
