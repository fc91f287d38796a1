#pragma once
// Iteration sources for sessions: CARMEN logs, ROS 1 bags (ros_bag_source.hpp) and the native
// sequence format.
//
// Native sequence (`*.seq.jsonl`): JSON Lines. The first line is a header,
//     {"scanloc_sequence": 1, "mounting": [x_m, y_m, yaw_rad]}      (mounting optional)
// then one iteration per line:
//     {"timestamp_s": 12.5,
//      "scan": {"angle_min_rad": -3.14159, "angle_increment_rad": 0.0026, "range_min_m": 0,
//               "range_max_m": 20, "ranges": [1.23, -1, ...], "reflectance": [...]},
//      "odometry": [x_m, y_m, yaw_rad],                               (optional, T_odom_robot)
//      "candidates": [[x_m, y_m, yaw_rad], ...],                      (optional, T_world_robot)
//      "truth": [x_m, y_m, yaw_rad]}                                  (optional, T_world_robot)
// Ranges of -1 (or null) carry no echo; a scan has 1 to kMaxBeamsPerScan beams; coordinates are
// finite and within ±kMaxCoordinateM. Errors name the file and line; a file without a single
// scan is an error too (ParseError "no scan in FILE" from Next()), so is a line over
// kMaxLineBytes.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "scanloc/io/carmen_log.hpp"
#include "scanloc/io/odometry_reversal.hpp"
#include "scanloc/io/ros_bag_source.hpp"
#include "scanloc/io/trajectory.hpp"
#include "scanloc/session/iteration.hpp"

namespace scanloc {

// One iteration per laser message (FLASER, ROBOTLASER1 or RAWLASER1: CarmenReader), its odometry
// the message's own (RAWLASER1: the latest ODOM's), repaired where the log's pose moved forward
// while the robot reversed (options.repair_reversed_odometry).
class CarmenIterationSource : public IterationSource {
 public:
  explicit CarmenIterationSource(const std::string& path, CarmenOptions options = {});
  bool Next(Iteration& iteration) override;
  LaserMounting mounting() const override { return reader_.mounting(); }
  double Progress() const override { return reader_.Progress(); }
  // Odometry increments reversed so far (0 when the repair is off).
  std::size_t repaired_odometry_increments() const override { return reversal_.repaired(); }
  // Scans so far whose timestamp is not after the previous scan's (backwards or repeated); they
  // are returned all the same.
  std::size_t timestamp_warnings() const override { return timestamps_.not_increasing(); }
  std::size_t zero_timestamps() const override { return timestamps_.zero(); }
  std::optional<double> no_return_m() const override { return reader_.no_return_m(); }
  std::optional<double> recognised_no_return_m() const override {
    return reader_.recognised_no_return_m();
  }
  std::map<std::string, std::size_t> skipped_messages() const override {
    return reader_.skipped_messages();
  }
  std::size_t ignored_laser_offsets() const override { return reader_.ignored_laser_offsets(); }

 private:
  std::string path_;
  bool repair_;
  CarmenReader reader_;
  OdometryReversalRepair reversal_;
  TimestampOrder timestamps_;
};

class SequenceFileSource : public IterationSource {
 public:
  explicit SequenceFileSource(const std::string& path);
  ~SequenceFileSource() override;
  bool Next(Iteration& iteration) override;
  LaserMounting mounting() const override { return mounting_; }
  // The ground-truth posture of the last iteration returned, when the sequence has one.
  const std::optional<Pose2D>& truth() const { return truth_; }
  double Progress() const override;
  // Iterations so far whose timestamp is not after the previous one's (backwards or repeated);
  // they are returned all the same.
  std::size_t timestamp_warnings() const override { return timestamps_.not_increasing(); }
  std::size_t zero_timestamps() const override { return timestamps_.zero(); }

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  LaserMounting mounting_;
  std::optional<Pose2D> truth_;
  TimestampOrder timestamps_;
};

// Writes a native sequence, atomically (a temporary file synced and renamed by Close(), which
// throws naming the path and the reason when a write failed).
class SequenceFileWriter {
 public:
  SequenceFileWriter(const std::string& path, const LaserMounting& mounting);
  ~SequenceFileWriter();
  SequenceFileWriter(const SequenceFileWriter&) = delete;
  SequenceFileWriter& operator=(const SequenceFileWriter&) = delete;
  void Write(const Iteration& iteration, const std::optional<Pose2D>& truth = std::nullopt);
  void Close();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// A source for a path, by its content whatever its name (DetectInputFormat): CARMEN log, ROS 1 bag
// or native sequence. Throws std::runtime_error listing the accepted formats for anything else.
std::unique_ptr<IterationSource> OpenIterationSource(const std::string& path,
                                                     CarmenOptions carmen = {},
                                                     RosBagOptions bag = {});

}  // namespace scanloc
