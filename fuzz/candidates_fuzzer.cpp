// ReadCandidatesFile (`x y theta [label]` lines) on arbitrary bytes; every posture it returns must
// be finite and labelled.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "scanloc/io/candidates_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const scanloc::fuzz::InputFile input(".txt");
  const std::string& path = input.Write(data, size);
  scanloc::fuzz::AcceptDocumentedErrors([&] {
    for (const scanloc::Candidate& candidate : scanloc::ReadCandidatesFile(path)) {
      const scanloc::Pose2D& pose = candidate.T_world_robot;
      scanloc::fuzz::Require(
          std::isfinite(pose.x_m) && std::isfinite(pose.y_m) && std::isfinite(pose.yaw_rad),
          "ReadCandidatesFile returned a non-finite posture");
      scanloc::fuzz::Require(!candidate.label.empty(), "ReadCandidatesFile returned no label");
    }
  });
  return 0;
}
