#pragma once

#include <string>

#include "scanloc/geometry/pose2d.hpp"

namespace scanloc {

// A candidate posture of the robot, named as in the chapter's tables (p0, p1, ...).
struct Candidate {
  Pose2D T_world_robot;
  std::string label;
  // Rule 2's E_max for this candidate and its refinement, m, when its place has its own (a map
  // that fits its own scans worse there: session/place_bound.hpp); 0: the options' bound.
  double max_expect_value_m = 0.0;
};

}  // namespace scanloc
