#pragma once
// The native scan file: a small text format for one laser scan.
//
//     # anything after '#' is a comment
//     scanloc_scan 1                  # format name and version, first non-comment line
//     beams 2400
//     angle_min_rad -3.14159265358979
//     angle_increment_rad 0.00261799387799
//     range_min_m 0                   # optional, default 0
//     range_max_m 20                  # optional, default 20
//     timestamp_s 12.5                # optional
//     ranges                          # then exactly `beams` numbers, any number per line;
//     1.234 1.236 -1 nan ...          # -1, nan, inf, ≤ range_min or ≥ range_max mean no echo
//     reflectance                     # optional, then exactly `beams` numbers
//     ...

#include <string>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/io/carmen_log.hpp"

namespace scanloc {

// Throws ParseError (file, line, what was expected) on malformed content.
LaserScan ReadScanFile(const std::string& path);
// Writes atomically.
void WriteScanFile(const LaserScan& scan, const std::string& path);

// Reads a scan from a native scan file, or the index-th laser scan of a CARMEN log (.clf, .log,
// optionally .gz) read with `carmen`.
LaserScan LoadScan(const std::string& path, std::size_t carmen_index = 0,
                   const CarmenOptions& carmen = {});

}  // namespace scanloc
