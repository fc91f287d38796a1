#pragma once
// Scoring a posture: the map simulated from it (3.1)–(3.7), then the Likelihood Test (3.8)–(3.10)
// and the Likelihood Distance (§3.5) of the real scan against that simulated scan. Every stage
// above (candidate evaluation, refinement, localisation) judges postures through this.

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
