// What one closure's solve costs on a real graph: reads a session's graph.g2o, adds one closure
// between its middle and its last node that disagrees with them by (6 cm, −3 cm, 0.01 rad), and
// solves the graph from the same start again and again, printing each solve's CPU time, the
// median and the iterations. Two builds of scanloc can then be set side by side on one graph
// (run them interleaved; the machine is shared).
//
//   pose_graph_solve_harness GRAPH.g2o [REPETITIONS]

#include <algorithm>
#include <cstdio>
#include <ctime>
#include <exception>
#include <stdexcept>
#include <string>
#include <vector>

#include "scanloc/graph/pose_graph.hpp"
#include "scanloc/io/g2o_file.hpp"

namespace {

using namespace scanloc;

double CpuSeconds() {
  return static_cast<double>(std::clock()) / CLOCKS_PER_SEC;
}

// The graph with one closure added that the nodes disagree with: a solve has work to do.
PoseGraph WithOneClosure(PoseGraph graph) {
  const std::size_t count = graph.nodes().size();
  if (count < 3) throw std::runtime_error("the graph needs at least 3 nodes");
  const std::size_t from = count / 2, to = count - 1;
  const Pose2D now = Between(graph.nodes()[from], graph.nodes()[to]);
  PoseGraphEdge closure;
  closure.from = from;
  closure.to = to;
  closure.T_from_to = Pose2D(now.x_m + 0.06, now.y_m - 0.03, now.yaw_rad + 0.01);
  closure.information = Eigen::Matrix3d::Identity() * 1e4;  // σ 1 cm, 0.01 rad
  closure.kind = EdgeKind::kClosure;
  graph.AddEdge(closure);
  return graph;
}

}  // namespace

int main(int argc, char** argv) {
  if (argc < 2 || argc > 3) {
    std::fprintf(stderr, "usage: %s GRAPH.g2o [REPETITIONS]\n", argv[0]);
    return 2;
  }
  try {
    const int repetitions = argc == 3 ? std::max(1, std::stoi(argv[2])) : 5;
    const PoseGraph start = WithOneClosure(ReadG2o(argv[1]));
    std::printf("%zu nodes, %zu edges\n", start.nodes().size(), start.edges().size());
    std::vector<double> seconds;
    for (int r = 0; r < repetitions; ++r) {
      PoseGraph graph = start;
      const double begin = CpuSeconds();
      const PoseGraphSummary summary = graph.Optimise();
      seconds.push_back(CpuSeconds() - begin);
      std::printf("solve %d: %.4f CPU s, %d iterations, cost %.3f -> %.3f\n", r + 1, seconds.back(),
                  summary.iterations, summary.initial_cost, summary.final_cost);
    }
    std::sort(seconds.begin(), seconds.end());
    std::printf("median %.4f CPU s over %d solves\n", seconds[seconds.size() / 2], repetitions);
  } catch (const std::exception& error) {
    std::fprintf(stderr, "error: %s\n", error.what());
    return 1;
  }
  return 0;
}
