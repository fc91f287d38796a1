#pragma once
// Helpers shared by the tests: synthetic rooms, layouts, the public datasets' location.

#include <string>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/maps/line_map.hpp"
#include "scanloc/simulation/simulated_scan.hpp"

namespace scanloc::testing {

// An axis-aligned rectangular room [0, width] × [0, height] as four segments.
LineMap RectangleRoom(double width_m, double height_m);

// A LaserScan whose ranges are the given simulated scan's (no-return beams become -1.0).
LaserScan ScanFromSimulation(const SimulatedScan& simulated);

// The folder of the public benchmark logs (SCANLOC_DATASETS, else ../shared/datasets), or "" when
// it does not exist.
std::string DatasetsDir();

// A fresh temporary directory for one test.
std::string TemporaryDir();

}  // namespace scanloc::testing
