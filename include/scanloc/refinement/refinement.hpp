#pragma once
// What every refinement method (Ceres, Error Descent, ICP) takes and returns, so they can be run
// and compared through one interface.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/geometry/pose2d.hpp"
#include "scanloc/likelihood/likelihood_distance.hpp"
#include "scanloc/likelihood/likelihood_test.hpp"
#include "scanloc/simulation/simulated_scan.hpp"

namespace scanloc {

// The scoring shared by all methods: how a posture is judged before and after refinement.
struct ScoringOptions {
  LikelihoodTestOptions test;
  LikelihoodDistanceOptions distance;
  PointSimulationOptions simulation;
};

struct RefinementResult {
  Pose2D T_world_laser;    // the refined posture of the laser
  bool converged = false;  // the method's own stopping criterion was met
  int iterations = 0;      // outer iterations (Ceres: re-simulations; ED: steps examined)
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

// Scores a posture: simulates the map from T_world_laser and runs both tests.
struct PostureScore {
  SimulatedScan simulated;
  LikelihoodTestResult test;
  LikelihoodDistanceResult distance;
};
PostureScore ScorePosture(const MapView& map, const LaserScan& scan, const Pose2D& T_world_laser,
                          const ScoringOptions& options);
// Scores many postures. Those that share the laser's position and differ in heading by whole
// beam steps see one simulated scan shifted by those steps: a single simulation over the widened
// sweep serves them all (what heading candidates cost, 5 simulations for ±10° by 5°, becomes about
// one). The scores equal ScorePosture's for each posture.
std::vector<PostureScore> ScorePostures(const MapView& map, const LaserScan& scan,
                                        const std::vector<Pose2D>& T_world_laser,
                                        const ScoringOptions& options);

}  // namespace scanloc
