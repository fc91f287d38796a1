// LoadPointMapPcdWithReport (a PCD point map, any of PCL's encodings) on arbitrary bytes; the
// report must add up. PCL itself is not instrumented: only scanloc's side gets coverage feedback,
// but a crash or memory error inside PCL's reader is still caught.
#include <pcl/console/print.h>

#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "scanloc/maps/point_map_io.hpp"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  pcl::console::setVerbosityLevel(pcl::console::L_ALWAYS);  // PCL prints every rejected header
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const scanloc::fuzz::InputFile input(".pcd");
  const std::string& path = input.Write(data, size);
  scanloc::fuzz::AcceptDocumentedErrors([&] {
    const scanloc::PointMapPcdLoad load = scanloc::LoadPointMapPcdWithReport(path);
    const std::size_t dropped = load.non_finite_points_skipped + load.points_merged;
    scanloc::fuzz::Require(dropped <= load.points_in_file, "the PCD load report does not add up");
  });
  return 0;
}
