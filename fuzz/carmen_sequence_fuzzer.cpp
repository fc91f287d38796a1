// A CARMEN log read as a session reads it: CarmenIterationSource, scan by scan with the odometry
// reversal repair, until the end or the first error; every iteration must carry a consistent scan
// and, when present, finite odometry.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "scanloc/io/sequence_sources.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const scanloc::fuzz::InputFile input(".clf");
  const std::string& path = input.Write(data, size);
  scanloc::fuzz::AcceptDocumentedErrors([&] {
    scanloc::CarmenIterationSource source(path);
    scanloc::Iteration iteration;
    while (source.Next(iteration)) {
      scanloc::fuzz::RequireConsistentScan(iteration.scan);
      if (iteration.odometry) {
        const scanloc::Pose2D& odometry = *iteration.odometry;
        scanloc::fuzz::Require(std::isfinite(odometry.x_m) && std::isfinite(odometry.y_m) &&
                                   std::isfinite(odometry.yaw_rad),
                               "CarmenIterationSource returned non-finite odometry");
      }
    }
    source.mounting();
  });
  return 0;
}
