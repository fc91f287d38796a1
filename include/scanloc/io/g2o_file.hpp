#pragma once
// The pose graph in g2o's text format, which g2o, GTSAM and their viewers read:
//   VERTEX_SE2 id x y θ
//   EDGE_SE2 from to dx dy dθ I11 I12 I13 I22 I23 I33   (upper triangle of the information)
//   FIX id
// Vertex ids are the node indices. The format has no edge kinds; as in the g2o benchmark graphs, an
// edge between consecutive vertices is read as sequential and any other as a closure.

#include <string>

#include "scanloc/graph/pose_graph.hpp"

namespace scanloc {

// Writes `graph` to `path` whole or not at all, with `fixed_node` as its FIX line. Closures the
// graph set aside (inactive edges) are left out: g2o, GTSAM or ReadG2o would take them for
// measurements; iterations.jsonl keeps every closure tried.
void WriteG2o(const PoseGraph& graph, const std::string& path, std::size_t fixed_node = 0);

// Reads a g2o SE(2) graph. Vertex ids must run 0, 1, 2, … in the order written; edges name known
// vertices. Other g2o records (VERTEX_XY, EDGE_SE2_XY, …) and FIX are skipped. Throws ParseError
// (file, line, what was expected) on anything else.
PoseGraph ReadG2o(const std::string& path);

}  // namespace scanloc
