#include "test_support.hpp"

#include <cstdlib>
#include <filesystem>

namespace scanloc::testing {

LineMap RectangleRoom(double width_m, double height_m) {
  LineMap map;
  map.segments = {{{0, 0}, {width_m, 0}},
                  {{width_m, 0}, {width_m, height_m}},
                  {{width_m, height_m}, {0, height_m}},
                  {{0, height_m}, {0, 0}}};
  return map;
}

LaserScan ScanFromSimulation(const SimulatedScan& simulated) {
  LaserScan scan;
  scan.layout = simulated.layout;
  scan.ranges_m = simulated.ranges_m;
  return scan;
}

std::string DatasetsDir() {
  const char* env = std::getenv("SCANLOC_DATASETS");
  const std::string dir = env != nullptr && *env != '\0' ? env : SCANLOC_DEFAULT_DATASETS;
  return std::filesystem::is_directory(dir) ? dir : "";
}

std::string TemporaryDir() {
  auto base = std::filesystem::temp_directory_path() / "scanloc-test-XXXXXX";
  std::string pattern = base.string();
  if (::mkdtemp(pattern.data()) == nullptr) throw std::runtime_error("mkdtemp failed");
  return pattern;
}

}  // namespace scanloc::testing
