// ReadTumTrajectory (`t x y z qx qy qz qw`), ReadCorrectedPoses (`t x y theta`) and
// ReadReferencePoses (either, told apart by the first line) on the same arbitrary bytes; every pose
// they return must be finite.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "fuzz_support.hpp"
#include "scanloc/io/trajectory.hpp"

namespace {

void RequireFinite(const std::vector<scanloc::StampedPose>& poses, const char* what) {
  for (const scanloc::StampedPose& stamped : poses)
    scanloc::fuzz::Require(std::isfinite(stamped.timestamp_s) && std::isfinite(stamped.pose.x_m) &&
                               std::isfinite(stamped.pose.y_m) &&
                               std::isfinite(stamped.pose.yaw_rad),
                           what);
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const scanloc::fuzz::InputFile input(".tum");
  const std::string& path = input.Write(data, size);
  scanloc::fuzz::AcceptDocumentedErrors([&] {
    RequireFinite(scanloc::ReadTumTrajectory(path), "ReadTumTrajectory returned a non-finite pose");
  });
  scanloc::fuzz::AcceptDocumentedErrors([&] {
    RequireFinite(scanloc::ReadCorrectedPoses(path),
                  "ReadCorrectedPoses returned a non-finite pose");
  });
  scanloc::fuzz::AcceptDocumentedErrors([&] {
    RequireFinite(scanloc::ReadReferencePoses(path),
                  "ReadReferencePoses returned a non-finite pose");
  });
  return 0;
}
