// ReadG2o (VERTEX_SE2 / EDGE_SE2 / FIX) on arbitrary bytes; a small graph it returns is then
// optimised, and every node must stay finite.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "scanloc/graph/pose_graph.hpp"
#include "scanloc/io/g2o_file.hpp"

namespace {

// Larger graphs are only read: solving them would slow the fuzzer without reaching new code.
constexpr std::size_t kMaxSolvedNodes = 64;

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const scanloc::fuzz::InputFile input(".g2o");
  const std::string& path = input.Write(data, size);
  scanloc::fuzz::AcceptDocumentedErrors([&] {
    scanloc::PoseGraph graph = scanloc::ReadG2o(path);
    if (graph.nodes().empty() || graph.nodes().size() > kMaxSolvedNodes) return;
    scanloc::PoseGraphOptions options;
    options.max_iterations = 10;
    graph.Optimise(options);
    for (const scanloc::Pose2D& node : graph.nodes())
      scanloc::fuzz::Require(
          std::isfinite(node.x_m) && std::isfinite(node.y_m) && std::isfinite(node.yaw_rad),
          "Optimise left a node that is not finite");
  });
  return 0;
}
