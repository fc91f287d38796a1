#pragma once
// A point map as a binary PCD file that other point-cloud tools open: float fields x, y, z (z = 0)
// `spacing`, the point's local spacing in metres (PointMap::spacing), and `normal_x normal_y`, the
// unit normal of the surface it samples (zero when unknown; PointMap::normal).

#include <cstddef>
#include <string>

#include "scanloc/maps/point_map.hpp"

namespace scanloc {

// Writes atomically (temporary sibling, fsync, rename) with plain writes, the bytes of PCL's binary
// writer; throws std::runtime_error naming the path and the system's reason (a full disk, say)
// when the file cannot be written, leaving no temporary behind. Coordinates are stored as float,
// each nudged within float precision so that it stays in its de-duplication cell: loading with the
// map's own options then gives back every point.
void SavePointMapPcd(const PointMap& map, const std::string& path);

struct PointMapPcdLoad {
  PointMap map;
  std::size_t points_in_file = 0;             // the cloud's width × height
  std::size_t non_finite_points_skipped = 0;  // NaN or infinite x or y: skipped
  std::size_t default_spacings_used = 0;      // no `spacing` field, or not finite and positive
  std::size_t points_merged = 0;              // fell in a de-duplication cell already taken
};

// Reads a PCD (any of PCL's encodings) with float or double fields x and y; z and other fields
// are ignored. A point's spacing comes from the `spacing` field when present and valid, else from
// options.cell_size_m (0.05 m when that is 0). Throws std::runtime_error naming the path and the
// problem when the file is missing, unreadable or has no x or y field, or a point beyond
// ±kMaxCoordinateM; non-finite points are skipped and counted. The header is checked before PCL
// reads it (ParseError with its line): sizes of 1, 2, 4 or 8 bytes, counts that agree, and no
// more points than the file's bytes can hold.
PointMapPcdLoad LoadPointMapPcdWithReport(const std::string& path, PointMapOptions options = {});
// The same, without the report.
PointMap LoadPointMapPcd(const std::string& path, PointMapOptions options = {});

}  // namespace scanloc
