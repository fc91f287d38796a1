#pragma once
// §3.2 The simulated scan: what the laser would see from a candidate posture, with the real scan's
// angular layout, from a line map, a point map, or both.

#include <cstdint>
#include <vector>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/geometry/pose2d.hpp"

namespace scanloc {

struct LineMap;
class PointMap;

// The map a scan is simulated from: a line map, a point map, or both (either may be null).
struct MapView {
  const LineMap* lines = nullptr;
  const PointMap* points = nullptr;
  bool empty() const;
};

enum class HitSource : std::uint8_t { kNone, kSegment, kPoint };

struct SimulatedScan {
  ScanLayout layout;
  std::vector<double> ranges_m;              // kNoReturn where the beam meets nothing within range
  std::vector<HitSource> hit_source;         // what each beam hit
  std::vector<std::int32_t> hit_index;       // segment or point index, -1 for none
  static constexpr double kNoReturn = -1.0;  // the trials' flag for "no data"

  std::size_t size() const { return ranges_m.size(); }
  bool IsValid(std::size_t beam) const { return hit_source[beam] != HitSource::kNone; }
};

struct PointSimulationOptions {
  // A map point hides the beams within ±(footprint_factor · spacing / 2) / range of its bearing,
  // where spacing is the point's local spacing: a sampled surface then occludes what lies behind
  // it instead of letting far points show through its gaps. 0 gives the chapter's (3.7) binning.
  double footprint_factor = 1.0;
};

// (3.1)–(3.5) Ray–segment intersection for every beam, nearest kept (occlusion).
SimulatedScan SimulateFromLines(const LineMap& map, const ScanLayout& layout,
                                const Pose2D& T_world_laser);
// (3.7) Map points within range_max of the laser, binned by bearing, nearest kept (of equal
// ranges, the lowest point index). The map's blocks are walked front to back, skipping those the
// beams cannot see past nearer hits: the cost follows what the scan sees, not the map's size.
SimulatedScan SimulateFromPoints(const PointMap& map, const ScanLayout& layout,
                                 const Pose2D& T_world_laser,
                                 const PointSimulationOptions& options = {});
// The same over every map point without the spatial index: the reference the index is checked
// and benchmarked against.
SimulatedScan SimulateFromPointsBruteForce(const PointMap& map, const ScanLayout& layout,
                                           const Pose2D& T_world_laser,
                                           const PointSimulationOptions& options = {});
// Both maps: the nearer hit per beam.
SimulatedScan Simulate(const MapView& map, const ScanLayout& layout, const Pose2D& T_world_laser,
                       const PointSimulationOptions& options = {});

}  // namespace scanloc
