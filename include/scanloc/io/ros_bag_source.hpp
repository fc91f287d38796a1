#pragma once
// Sessions from ROS 1 bags (no ROS installation needed): sensor_msgs/LaserScan scans with odometry
// from nav_msgs/Odometry or from /tf, interpolated to each scan's stamp, and the laser's mounting
// from /tf_static. Read streaming, message by message, like the CARMEN reader.

#include <memory>
#include <optional>
#include <string>

#include "scanloc/session/iteration.hpp"

namespace scanloc {

struct RosBagOptions {
  std::string scan_topic = "/scan";  // sensor_msgs/LaserScan
  // nav_msgs/Odometry; when the bag has no such topic, odometry comes from /tf (odom_frame →
  // base_frame), and when it has neither, scans carry no odometry.
  std::string odometry_topic = "/odom";
  std::string odom_frame = "odom";
  std::string base_frame = "base_link";
  // T_robot_laser; overrides /tf_static (base_frame → the scan's frame_id) when set.
  std::optional<Pose2D> mounting;
  // A scan before the first or after the last odometry sample takes the nearest one when it is at
  // most this far in time; otherwise it carries no odometry. Also how long (bag time) a scan waits
  // for an odometry sample after its stamp before it is delivered. Seconds, >= 0.
  double odometry_tolerance_s = 0.5;
  // Throws std::invalid_argument for an empty topic or frame, or a negative or non-finite
  // tolerance.
  void Validate() const;
};

// True when this build reads ROS bags (the Debian rosbag_storage libraries were found).
bool RosBagSupported();

// One iteration per LaserScan on options.scan_topic. Ranges that are NaN, ±inf, at or below
// range_min or at or beyond range_max carry no echo; float32 values are taken at their shortest
// decimal form (the value they were written from, e.g. 3.45 rather than 3.4500000477). A scan with
// a negative angle_increment is reversed so that bearings increase.
class RosBagIterationSource : public IterationSource {
 public:
  // Throws std::runtime_error naming the bag when it cannot be opened, holds no LaserScan on the
  // scan topic (listing the LaserScan topics it has), or has /tf_static without a path from
  // base_frame to the scan's frame. Without /tf_static (and no options.mounting) the laser sits at
  // the robot's origin.
  explicit RosBagIterationSource(const std::string& path, RosBagOptions options = {});
  ~RosBagIterationSource() override;
  RosBagIterationSource(const RosBagIterationSource&) = delete;
  RosBagIterationSource& operator=(const RosBagIterationSource&) = delete;

  bool Next(Iteration& iteration) override;
  LaserMounting mounting() const override;
  // The fraction of the bag's messages read so far, in [0, 1].
  double Progress() const override;
  // "odometry topic /odom", "tf odom → base_link" or "none".
  std::string OdometrySource() const;

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

}  // namespace scanloc
