#include "scanloc/io/g2o_file.hpp"

#include <fstream>
#include <iomanip>
#include <ostream>
#include <stdexcept>
#include <vector>

#include "scanloc/common/atomic_file.hpp"
#include "scanloc/common/bounded_line.hpp"
#include "scanloc/common/parse_error.hpp"

namespace scanloc {
namespace {

// EDGE_SE2 from to dx dy dθ and six information entries.
constexpr std::size_t kEdgeFields = 12;
// VERTEX_SE2 id x y θ
constexpr std::size_t kVertexFields = 5;

std::size_t ParseId(const std::string& field, const std::string& path, std::size_t line) {
  const long id = ParseInteger(field, path, line, "a vertex id");
  if (id < 0) throw ParseError(path, line, "expected a vertex id ≥ 0, got " + field);
  return static_cast<std::size_t>(id);
}

void ReadVertex(const std::vector<std::string>& fields, const std::string& path, std::size_t line,
                PoseGraph& graph) {
  if (fields.size() != kVertexFields)
    throw ParseError(path, line, "expected 'VERTEX_SE2 id x y theta'");
  const std::size_t id = ParseId(fields[1], path, line);
  if (id != graph.nodes().size())
    throw ParseError(path, line,
                     "expected vertex " + std::to_string(graph.nodes().size()) + ", got " +
                         fields[1] + " (ids run 0, 1, 2, … in order)");
  const Pose2D pose(ParseFiniteDouble(fields[2], path, line, "x"),
                    ParseFiniteDouble(fields[3], path, line, "y"),
                    ParseFiniteDouble(fields[4], path, line, "theta"));
  if (!IsPlausiblePose(pose)) throw ParseError(path, line, "expected a vertex within ±1000 km");
  graph.AddNode(pose);
}

void ReadEdge(const std::vector<std::string>& fields, const std::string& path, std::size_t line,
              PoseGraph& graph) {
  if (fields.size() != kEdgeFields)
    throw ParseError(path, line,
                     "expected 'EDGE_SE2 from to dx dy dtheta I11 I12 I13 I22 I23 I33'");
  PoseGraphEdge edge;
  edge.from = ParseId(fields[1], path, line);
  edge.to = ParseId(fields[2], path, line);
  edge.T_from_to = Pose2D(ParseFiniteDouble(fields[3], path, line, "dx"),
                          ParseFiniteDouble(fields[4], path, line, "dy"),
                          ParseFiniteDouble(fields[5], path, line, "dtheta"));
  double entries[6];
  for (int i = 0; i < 6; ++i)
    entries[i] = ParseFiniteDouble(fields[6 + i], path, line, "an information entry");
  edge.information << entries[0], entries[1], entries[2], entries[1], entries[3], entries[4],
      entries[2], entries[4], entries[5];
  const std::size_t gap = edge.from > edge.to ? edge.from - edge.to : edge.to - edge.from;
  edge.kind = gap == 1 ? EdgeKind::kSequential : EdgeKind::kClosure;
  try {
    graph.AddEdge(edge);
  } catch (const std::invalid_argument& error) {
    throw ParseError(path, line, error.what());
  }
}

}  // namespace

void WriteG2o(const PoseGraph& graph, const std::string& path, std::size_t fixed_node) {
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << std::setprecision(17);
    for (std::size_t i = 0; i < graph.nodes().size(); ++i) {
      const Pose2D& pose = graph.nodes()[i];
      out << "VERTEX_SE2 " << i << ' ' << pose.x_m << ' ' << pose.y_m << ' ' << pose.yaw_rad
          << '\n';
    }
    for (const PoseGraphEdge& edge : graph.edges()) {
      if (!edge.active) continue;  // a closure the graph set aside: a reader would believe it
      const Eigen::Matrix3d& info = edge.information;
      out << "EDGE_SE2 " << edge.from << ' ' << edge.to << ' ' << edge.T_from_to.x_m << ' '
          << edge.T_from_to.y_m << ' ' << edge.T_from_to.yaw_rad << ' ' << info(0, 0) << ' '
          << info(0, 1) << ' ' << info(0, 2) << ' ' << info(1, 1) << ' ' << info(1, 2) << ' '
          << info(2, 2) << '\n';
    }
    if (fixed_node < graph.nodes().size()) out << "FIX " << fixed_node << '\n';
  });
}

PoseGraph ReadG2o(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open pose graph " + path);
  PoseGraph graph;
  std::string text;
  std::size_t line = 0;
  while (ReadBoundedLine(in, text, path, ++line)) {
    const std::vector<std::string> fields = SplitFields(text, kEdgeFields);
    if (fields.empty()) continue;
    if (fields[0] == "VERTEX_SE2") {
      ReadVertex(fields, path, line, graph);
    } else if (fields[0] == "EDGE_SE2") {
      ReadEdge(fields, path, line, graph);
    } else if (fields[0].rfind("VERTEX_", 0) != 0 && fields[0].rfind("EDGE_", 0) != 0 &&
               fields[0] != "FIX") {
      throw ParseError(
          path, line, "expected a g2o record (VERTEX_SE2, EDGE_SE2, FIX), got '" + fields[0] + "'");
    }
  }
  if (in.bad()) throw std::runtime_error("error while reading pose graph " + path);
  return graph;
}

}  // namespace scanloc
