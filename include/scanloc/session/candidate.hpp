#pragma once

#include <string>

#include "scanloc/geometry/pose2d.hpp"

namespace scanloc {

// A candidate posture of the robot, named as in the chapter's tables (p0, p1, ...).
struct Candidate {
  Pose2D T_world_robot;
  std::string label;
};

}  // namespace scanloc
