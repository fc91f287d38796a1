#pragma once
// One iteration of a session, as a sequence source delivers it, and the sources' interface.

#include <cstddef>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/geometry/pose2d.hpp"

namespace scanloc {

struct Iteration {
  double timestamp_s = 0.0;
  LaserScan scan;
  std::optional<Pose2D> odometry;           // T_odom_robot at the scan's time, when known
  std::vector<Pose2D> external_candidates;  // T_world_robot postures from outside (if any)
  std::string origin;                       // where it came from, e.g. "intel.clf.gz:1234"
};

// Streams iterations one at a time, so that a session never holds the whole log.
class IterationSource {
 public:
  virtual ~IterationSource() = default;
  // Fills `iteration`; false at the end. Malformed input throws ParseError (file, line).
  virtual bool Next(Iteration& iteration) = 0;
  // The laser's mounting on the robot as the source knows it.
  virtual LaserMounting mounting() const = 0;
  // The fraction of the input read so far, in [0, 1]; 0 when unknown.
  virtual double Progress() const { return 0.0; }
  // Odometry increments the source repaired (CARMEN: moving forward while ODOM reported a
  // negative velocity); 0 for sources that repair nothing.
  virtual std::size_t repaired_odometry_increments() const { return 0; }
  // Scans so far whose timestamp is not after the previous scan's (backwards or repeated): they
  // are delivered all the same, and the session says how many there were.
  virtual std::size_t timestamp_warnings() const { return 0; }
  // Scans so far with a timestamp of exactly 0 (a log whose clock was not recorded).
  virtual std::size_t zero_timestamps() const { return 0; }
  // Readers of logs with a no-return code (CARMEN): the range limit in force for the laser, m, and
  // the saturation code recognised in the log (nullopt: none, or not looked for).
  virtual std::optional<double> no_return_m() const { return std::nullopt; }
  virtual std::optional<double> recognised_no_return_m() const { return std::nullopt; }
  // Messages of the input skipped so far, by type (CARMEN: NEFF, TRUEPOS, RAWLASER2, ...).
  virtual std::map<std::string, std::size_t> skipped_messages() const { return {}; }
  // Laser mountings announced after the first scan and ignored (CARMEN's late PARAM lines).
  virtual std::size_t ignored_laser_offsets() const { return 0; }
};

}  // namespace scanloc
