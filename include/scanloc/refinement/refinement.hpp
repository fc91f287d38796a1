#pragma once
// What every refinement method (Ceres, Error Descent, ICP) takes and returns, so they can be run
// and compared through one interface.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/geometry/pose2d.hpp"
#include "scanloc/likelihood/posture_scoring.hpp"

namespace scanloc {

struct RefinementResult {
  Pose2D T_world_laser;    // the refined posture of the laser
  bool converged = false;  // the method's own stopping criterion was met
  int iterations = 0;      // outer iterations (Ceres: re-simulations; ED: steps examined)
  // Ceres: the outer iterations came back to a posture they had started from, so they would
  // cycle with this period to the cap; the cap's posture was taken without running them (the
  // same result). 0 when they did not.
  int cycle_period = 0;
  LikelihoodTestResult test_before, test_after;
  LikelihoodDistanceResult distance_before, distance_after;
  // Covariance of (x, y, θ) in m², m·rad, rad²; valid only when has_covariance.
  Eigen::Matrix3d covariance = Eigen::Matrix3d::Zero();
  bool has_covariance = false;
  // The geometry constrains some direction poorly (a corridor): the posture is not to be trusted
  // along it. `degeneracy` says which.
  bool degenerate = false;
  std::string degeneracy;
  double time_s = 0.0;
};

}  // namespace scanloc
