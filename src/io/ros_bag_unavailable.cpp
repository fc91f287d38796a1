// Built instead of ros_bag_source.cpp when the rosbag_storage libraries are absent (see
// cmake/ScanlocRosBag.cmake): opening a bag then says how to get the support.
#include <stdexcept>

#include "scanloc/io/ros_bag_source.hpp"

namespace scanloc {

struct RosBagIterationSource::Impl {};

void RosBagOptions::Validate() const {}

bool RosBagSupported() {
  return false;
}

RosBagIterationSource::RosBagIterationSource(const std::string& path, RosBagOptions) {
  throw std::runtime_error("cannot read ROS bag " + path +
                           ": this scanloc was built without ROS bag support (install "
                           "librosbag-storage-dev libsensor-msgs-dev libnav-msgs-dev "
                           "libtf2-msgs-dev, see scripts/install-deps.sh, and rebuild)");
}
RosBagIterationSource::~RosBagIterationSource() = default;
bool RosBagIterationSource::Next(Iteration&) {
  return false;
}
LaserMounting RosBagIterationSource::mounting() const {
  return {};
}
double RosBagIterationSource::Progress() const {
  return 0.0;
}
std::string RosBagIterationSource::OdometrySource() const {
  return "none";
}

}  // namespace scanloc
