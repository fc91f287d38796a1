// ReadRelations (`t1 t2 x y z roll pitch yaw` lines) on arbitrary bytes, then the relations metric
// against a trajectory made of the relations' own timestamps; every relation it returns must be
// finite.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fuzz_support.hpp"
#include "scanloc/evaluation/relations_evaluation.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const scanloc::fuzz::InputFile input(".relations");
  const std::string& path = input.Write(data, size);
  scanloc::fuzz::AcceptDocumentedErrors([&] {
    const std::vector<scanloc::Relation> relations = scanloc::ReadRelations(path);
    std::vector<scanloc::StampedPose> trajectory;
    for (const scanloc::Relation& relation : relations) {
      const scanloc::Pose2D& pose = relation.T_1_2;
      scanloc::fuzz::Require(std::isfinite(relation.t1_s) && std::isfinite(relation.t2_s) &&
                                 std::isfinite(pose.x_m) && std::isfinite(pose.y_m) &&
                                 std::isfinite(pose.yaw_rad),
                             "ReadRelations returned a non-finite relation");
      trajectory.push_back({relation.t1_s, scanloc::Pose2D()});
      trajectory.push_back({relation.t2_s, pose});
    }
    scanloc::EvaluateRelations(trajectory, relations);
  });
  return 0;
}
