// A ROS 1 bag read as a session reads it: RosBagIterationSource (LaserScan on /scan, odometry from
// /odom or /tf, the mounting from /tf_static), scan by scan until the end or the first error;
// every iteration must carry a consistent scan and, when present, finite odometry, and the
// mounting must be finite.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "scanloc/io/ros_bag_source.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const scanloc::fuzz::InputFile input(".bag");
  const std::string& path = input.Write(data, size);
  scanloc::fuzz::AcceptDocumentedErrors([&] {
    scanloc::RosBagIterationSource source(path, scanloc::RosBagOptions{});
    scanloc::fuzz::Require(scanloc::fuzz::FinitePose(source.mounting().T_robot_laser),
                           "RosBagIterationSource returned a non-finite mounting");
    scanloc::Iteration iteration;
    while (source.Next(iteration)) {
      scanloc::fuzz::RequireConsistentScan(iteration.scan);
      if (iteration.odometry)
        scanloc::fuzz::Require(scanloc::fuzz::FinitePose(*iteration.odometry),
                               "RosBagIterationSource returned non-finite odometry");
    }
  });
  return 0;
}
