// The only file that sees rosbag's headers (they pull in ROS 2's pluginlib): see
// cmake/ScanlocRosBag.cmake.
#include "scanloc/io/ros_bag_source.hpp"

#include <nav_msgs/Odometry.h>
#include <rosbag/bag.h>
#include <rosbag/view.h>
#include <sensor_msgs/LaserScan.h>
#include <tf2_msgs/TFMessage.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <deque>
#include <map>
#include <set>
#include <stdexcept>
#include <tuple>
#include <utility>
#include <vector>

#include "ros_bag_structure.hpp"

namespace scanloc {
namespace {

constexpr char kTfTopic[] = "/tf";
constexpr char kTfStaticTopic[] = "/tf_static";
constexpr char kLaserScanType[] = "sensor_msgs/LaserScan";
constexpr char kOdometryType[] = "nav_msgs/Odometry";

struct StampedOdometry {
  double stamp_s = 0.0;
  Pose2D pose;  // T_odom_robot
};

// The value a float32 field was written from: its shortest decimal form, read as a double.
double FloatAsDecimal(float value) {
  if (!std::isfinite(value)) return static_cast<double>(value);
  char text[32];
  const auto written = std::to_chars(text, text + sizeof text, value);
  double result = static_cast<double>(value);
  std::from_chars(text, written.ptr, result);
  return result;
}

// Fields of view that laser drivers derive their bearings from (180°, 240°, 270°, 360°).
constexpr double kCommonFieldsOfViewRad[] = {M_PI, 4.0 * M_PI / 3.0, 1.5 * M_PI, 2.0 * M_PI};

// The double-precision layout a float32 angle_min and angle_increment were rounded from, when they
// are a common field of view centred on the heading, in n or n − 1 steps (as CARMEN's logs and
// most drivers have them); otherwise their shortest decimal forms. A session then sees the same
// bearings from a bag as from the log it was converted from, to the last bit.
std::pair<double, double> RecoverBearings(float angle_min, float increment, std::size_t n) {
  for (const double fov : kCommonFieldsOfViewRad)
    for (const std::size_t steps : {n, n - 1}) {
      if (steps == 0) continue;
      const double exact_increment = fov / static_cast<double>(steps);
      for (const double sign : {1.0, -1.0})
        if (static_cast<float>(-sign * fov / 2.0) == angle_min &&
            static_cast<float>(sign * exact_increment) == increment)
          return {-sign * fov / 2.0, sign * exact_increment};
    }
  return {FloatAsDecimal(angle_min), FloatAsDecimal(increment)};
}

std::string FrameName(const std::string& frame) {
  return !frame.empty() && frame.front() == '/' ? frame.substr(1) : frame;
}

double YawOf(const geometry_msgs::Quaternion& q) {
  return std::atan2(2.0 * (q.w * q.z + q.x * q.y), 1.0 - 2.0 * (q.y * q.y + q.z * q.z));
}

Pose2D PlanarPose(const geometry_msgs::Transform& t) {
  return Pose2D(t.translation.x, t.translation.y, YawOf(t.rotation)).Normalized();
}

// `pose` as read from the bag, refused with what `describe()` says it is when a field is NaN or
// infinite (as read, or after composing or interpolating poses of huge but finite fields). The
// description is built only then: odometry passes here message by message.
template <typename Describe>
Pose2D RequireFinite(const Pose2D& pose, Describe&& describe) {
  if (std::isfinite(pose.x_m) && std::isfinite(pose.y_m) && std::isfinite(pose.yaw_rad))
    return pose;
  throw std::runtime_error(describe() + ": expected a finite pose, got (" +
                           std::to_string(pose.x_m) + ", " + std::to_string(pose.y_m) + ", " +
                           std::to_string(pose.yaw_rad) + ")");
}

LaserScan ToLaserScan(const sensor_msgs::LaserScan& message) {
  LaserScan scan;
  const std::size_t n = message.ranges.size();
  scan.timestamp_s = message.header.stamp.toSec();
  scan.layout.beam_count = n;
  std::tie(scan.layout.angle_min_rad, scan.layout.angle_increment_rad) =
      RecoverBearings(message.angle_min, message.angle_increment, n);
  scan.layout.range_min_m = FloatAsDecimal(message.range_min);
  scan.layout.range_max_m = FloatAsDecimal(message.range_max);
  scan.ranges_m.resize(n);
  for (std::size_t i = 0; i < n; ++i) scan.ranges_m[i] = FloatAsDecimal(message.ranges[i]);
  if (message.intensities.size() == n) {
    scan.reflectance.resize(n);
    for (std::size_t i = 0; i < n; ++i)
      scan.reflectance[i] = FloatAsDecimal(message.intensities[i]);
  }
  if (scan.layout.angle_increment_rad < 0.0 && n > 0) {  // bearings decreasing: reverse the beams
    scan.layout.angle_min_rad += static_cast<double>(n - 1) * scan.layout.angle_increment_rad;
    scan.layout.angle_increment_rad = -scan.layout.angle_increment_rad;
    std::reverse(scan.ranges_m.begin(), scan.ranges_m.end());
    std::reverse(scan.reflectance.begin(), scan.reflectance.end());
  }
  return scan;
}

// x, y linear and yaw along the shorter arc, at fraction w in [0, 1] from a to b.
Pose2D Interpolate(const Pose2D& a, const Pose2D& b, double w) {
  return Pose2D(a.x_m + w * (b.x_m - a.x_m), a.y_m + w * (b.y_m - a.y_m),
                a.yaw_rad + w * NormalizeAngle(b.yaw_rad - a.yaw_rad))
      .Normalized();
}

std::string TopicsOfType(rosbag::View& view, const std::string& type) {
  std::set<std::string> topics;
  for (const rosbag::ConnectionInfo* c : view.getConnections())
    if (c->datatype == type) topics.insert(c->topic);
  std::string list;
  for (const auto& topic : topics) list += (list.empty() ? "" : ", ") + topic;
  return list.empty() ? "none" : list;
}

// The message as a `Message`, or null when it is of another type; its serialised bytes are
// checked by `check` first, so that no length it announces is believed beyond its bytes.
template <class Message>
boost::shared_ptr<Message> Instantiate(const rosbag::MessageInstance& m,
                                       void (*check)(const std::uint8_t*, std::size_t),
                                       const std::string& path) {
  if (!m.isType<Message>()) return nullptr;
  std::vector<std::uint8_t> bytes(m.size());
  ros::serialization::OStream stream(bytes.data(), static_cast<std::uint32_t>(bytes.size()));
  m.write(stream);
  try {
    check(bytes.data(), bytes.size());
  } catch (const std::runtime_error& e) {
    throw std::runtime_error("ROS bag " + path + ": " + m.getTopic() + " message at bag time " +
                             std::to_string(m.getTime().toSec()) + ": " + e.what());
  }
  return m.instantiate<Message>();
}

boost::shared_ptr<sensor_msgs::LaserScan> AsLaserScan(const rosbag::MessageInstance& m,
                                                      const std::string& path) {
  return Instantiate<sensor_msgs::LaserScan>(m, bag::CheckLaserScanBytes, path);
}

bool HasTopic(rosbag::View& view, const std::string& topic, const std::string& type) {
  for (const rosbag::ConnectionInfo* c : view.getConnections())
    if (c->topic == topic && (type.empty() || c->datatype == type)) return true;
  return false;
}

}  // namespace

void RosBagOptions::Validate() const {
  if (scan_topic.empty() || odometry_topic.empty() || odom_frame.empty() || base_frame.empty())
    throw std::invalid_argument("RosBagOptions: topics and frames must not be empty");
  if (!(odometry_tolerance_s >= 0.0) || !std::isfinite(odometry_tolerance_s))
    throw std::invalid_argument("RosBagOptions: odometry_tolerance_s must be finite and >= 0");
  if (mounting && (!std::isfinite(mounting->x_m) || !std::isfinite(mounting->y_m) ||
                   !std::isfinite(mounting->yaw_rad)))
    throw std::invalid_argument("RosBagOptions: mounting must be finite");
}

bool RosBagSupported() {
  return true;
}

struct RosBagIterationSource::Impl {
  enum class OdometryFrom { kTopic, kTf, kNone };

  Impl(const std::string& bag_path, RosBagOptions bag_options)
      : path(bag_path), options(std::move(bag_options)) {
    options.Validate();
    bag::CheckBagStructure(path);  // before rosbag believes any length the file announces
    try {
      bag.open(path, rosbag::bagmode::Read);
    } catch (const rosbag::BagException& e) {
      throw std::runtime_error("cannot open ROS bag " + path + ": " + e.what());
    }
    rosbag::View all(bag);
    if (!HasTopic(all, options.scan_topic, kLaserScanType))
      throw std::runtime_error(
          "ROS bag " + path + ": no " + kLaserScanType + " on topic " + options.scan_topic +
          " (LaserScan topics in the bag: " + TopicsOfType(all, kLaserScanType) +
          "; choose one with --scan-topic)");
    odometry_from = HasTopic(all, options.odometry_topic, kOdometryType) ? OdometryFrom::kTopic
                    : HasTopic(all, kTfTopic, "")                        ? OdometryFrom::kTf
                                                                         : OdometryFrom::kNone;
    mounting.T_robot_laser = options.mounting ? *options.mounting : MountingFromTfStatic(all);
    std::vector<std::string> topics{options.scan_topic};
    if (odometry_from == OdometryFrom::kTopic) topics.push_back(options.odometry_topic);
    if (odometry_from == OdometryFrom::kTf) topics.push_back(kTfTopic);
    view = std::make_unique<rosbag::View>(bag, rosbag::TopicQuery(topics));
    total_messages = view->size();
    cursor = view->begin();
  }

  std::string FirstScanFrame() {
    rosbag::View scans(bag, rosbag::TopicQuery(options.scan_topic));
    for (const rosbag::MessageInstance& m : scans)
      if (auto scan = AsLaserScan(m, path)) return FrameName(scan->header.frame_id);
    return "";
  }

  // T_base_laser composed along /tf_static's parent links from the scan's frame up to base_frame.
  Pose2D MountingFromTfStatic(rosbag::View& all) {
    if (!HasTopic(all, kTfStaticTopic, "")) return Pose2D();
    std::map<std::string, std::pair<std::string, Pose2D>> parent_of;  // child → (parent, T_p_c)
    rosbag::View statics(bag, rosbag::TopicQuery(kTfStaticTopic));
    for (const rosbag::MessageInstance& m : statics)
      if (auto tf = Instantiate<tf2_msgs::TFMessage>(m, bag::CheckTfMessageBytes, path))
        for (const auto& t : tf->transforms)
          parent_of[FrameName(t.child_frame_id)] = {FrameName(t.header.frame_id),
                                                    PlanarPose(t.transform)};
    const std::string laser_frame = FirstScanFrame();
    const std::string base = FrameName(options.base_frame);
    Pose2D T_frame_laser;
    std::string frame = laser_frame;
    for (std::size_t hops = 0; frame != base; ++hops) {
      const auto link = parent_of.find(frame);
      if (link == parent_of.end() || hops > parent_of.size())
        throw std::runtime_error("ROS bag " + path + ": /tf_static has no path from " + base +
                                 " to the scan's frame '" + laser_frame +
                                 "' (give the mounting, e.g. --laser-offset, or --base-frame)");
      const std::string where = "ROS bag " + path + ": /tf_static's transform from '" +
                                link->second.first + "' to '" + frame + "'";
      T_frame_laser = RequireFinite(link->second.second, [&] { return where; }) * T_frame_laser;
      frame = link->second.first;
      RequireFinite(T_frame_laser, [&] { return where + ", composed up to '" + frame + "',"; });
    }
    return T_frame_laser.Normalized();
  }

  void AddOdometry(double stamp_s, const Pose2D& pose, const std::string& topic) {
    StampedOdometry sample{stamp_s, RequireFinite(pose, [&] {
                             return "ROS bag " + path + ": the odometry on " + topic + " stamped " +
                                    std::to_string(stamp_s) + " s";
                           })};
    auto at = std::upper_bound(
        odometry.begin(), odometry.end(), stamp_s,
        [](double t, const StampedOdometry& s) { return t < s.stamp_s; });  // usually the end
    odometry.insert(at, sample);
  }

  // Reads one message of the view into the pending scans or the odometry samples.
  void ReadMessage() {
    const rosbag::MessageInstance& m = *cursor;
    last_bag_time_s = m.getTime().toSec();
    if (m.getTopic() == options.scan_topic) {
      if (auto scan = AsLaserScan(m, path)) {
        Pending next{ToLaserScan(*scan),
                     path + ":" + options.scan_topic + "#" + std::to_string(scans_read)};
        try {
          next.scan.CheckConsistent();
        } catch (const std::invalid_argument& e) {
          throw std::runtime_error("ROS bag " + next.origin +
                                   ": expected a usable LaserScan: " + e.what());
        }
        pending.push_back(std::move(next));
        ++scans_read;
      }
    } else if (odometry_from == OdometryFrom::kTopic) {
      if (auto odom = Instantiate<nav_msgs::Odometry>(m, bag::CheckOdometryBytes, path)) {
        const auto& p = odom->pose.pose;
        AddOdometry(odom->header.stamp.toSec(),
                    Pose2D(p.position.x, p.position.y, YawOf(p.orientation)).Normalized(),
                    m.getTopic());
      }
    } else if (auto tf = Instantiate<tf2_msgs::TFMessage>(m, bag::CheckTfMessageBytes, path)) {
      for (const auto& t : tf->transforms)
        if (FrameName(t.header.frame_id) == FrameName(options.odom_frame) &&
            FrameName(t.child_frame_id) == FrameName(options.base_frame))
          AddOdometry(t.header.stamp.toSec(), PlanarPose(t.transform), m.getTopic());
    }
    ++cursor;
    ++messages_read;
  }

  // True when the odometry around the scan's stamp is known (or will never be).
  bool Ready(double stamp_s) const {
    if (odometry_from == OdometryFrom::kNone || cursor == view->end()) return true;
    if (!odometry.empty() && odometry.back().stamp_s >= stamp_s) return true;
    return last_bag_time_s > stamp_s + options.odometry_tolerance_s;
  }

  std::optional<Pose2D> OdometryAt(double t) const {
    if (odometry.empty()) return std::nullopt;
    const auto b =
        std::lower_bound(odometry.begin(), odometry.end(), t,
                         [](const StampedOdometry& s, double stamp) { return s.stamp_s < stamp; });
    if (b == odometry.end()) {
      const StampedOdometry& last = odometry.back();
      return t - last.stamp_s <= options.odometry_tolerance_s ? std::optional(last.pose)
                                                              : std::nullopt;
    }
    if (b->stamp_s == t) return b->pose;
    if (b == odometry.begin())
      return b->stamp_s - t <= options.odometry_tolerance_s ? std::optional(b->pose) : std::nullopt;
    const auto a = std::prev(b);
    return Interpolate(a->pose, b->pose, (t - a->stamp_s) / (b->stamp_s - a->stamp_s));
  }

  bool Next(Iteration& iteration) {
    while (pending.empty() || !Ready(pending.front().scan.timestamp_s)) {
      if (cursor == view->end()) {
        if (pending.empty()) return false;
        break;
      }
      ReadMessage();
    }
    Pending next = std::move(pending.front());
    pending.pop_front();
    iteration = Iteration{};
    iteration.timestamp_s = next.scan.timestamp_s;
    iteration.odometry = OdometryAt(iteration.timestamp_s);
    if (iteration.odometry)
      RequireFinite(*iteration.odometry, [&] {
        return "ROS bag " + next.origin + ": the odometry interpolated at the scan's stamp";
      });
    iteration.origin = std::move(next.origin);
    iteration.scan = std::move(next.scan);
    // Samples before the one bracketing this scan are no longer needed (stamps only grow).
    while (odometry.size() > 2 && odometry[1].stamp_s <= iteration.timestamp_s)
      odometry.pop_front();
    return true;
  }

  struct Pending {
    LaserScan scan;
    std::string origin;
  };

  std::string path;
  RosBagOptions options;
  rosbag::Bag bag;
  std::unique_ptr<rosbag::View> view;
  rosbag::View::iterator cursor;
  OdometryFrom odometry_from = OdometryFrom::kNone;
  LaserMounting mounting;
  std::deque<Pending> pending;
  std::deque<StampedOdometry> odometry;
  double last_bag_time_s = 0.0;
  std::size_t total_messages = 0, messages_read = 0, scans_read = 0;
};

RosBagIterationSource::RosBagIterationSource(const std::string& path, RosBagOptions options) {
  try {
    impl_ = std::make_unique<Impl>(path, std::move(options));
  } catch (const rosbag::BagException& e) {
    throw std::runtime_error("ROS bag " + path + ": " + e.what());
  } catch (const ros::Exception& e) {
    throw std::runtime_error("ROS bag " + path + ": malformed message: " + e.what());
  }
}
RosBagIterationSource::~RosBagIterationSource() = default;

bool RosBagIterationSource::Next(Iteration& iteration) {
  try {
    return impl_->Next(iteration);
  } catch (const rosbag::BagException& e) {
    throw std::runtime_error("ROS bag " + impl_->path + ": " + e.what());
  } catch (const ros::Exception& e) {  // a message that does not deserialise
    throw std::runtime_error("ROS bag " + impl_->path + ": malformed message: " + e.what());
  }
}

LaserMounting RosBagIterationSource::mounting() const {
  return impl_->mounting;
}

double RosBagIterationSource::Progress() const {
  return impl_->total_messages == 0 ? 0.0
                                    : static_cast<double>(impl_->messages_read) /
                                          static_cast<double>(impl_->total_messages);
}

std::string RosBagIterationSource::OdometrySource() const {
  switch (impl_->odometry_from) {
    case Impl::OdometryFrom::kTopic:
      return "odometry topic " + impl_->options.odometry_topic;
    case Impl::OdometryFrom::kTf:
      return "tf " + impl_->options.odom_frame + " → " + impl_->options.base_frame;
    case Impl::OdometryFrom::kNone:
      break;
  }
  return "none";
}

}  // namespace scanloc
