#include "scanloc/refinement/refinement.hpp"

namespace scanloc {

PostureScore ScorePosture(const MapView& map, const LaserScan& scan, const Pose2D& T_world_laser,
                          const ScoringOptions& options) {
  PostureScore score;
  score.simulated = Simulate(map, scan.layout, T_world_laser, options.simulation);
  score.test = RunLikelihoodTest(scan, score.simulated, options.test);
  score.distance = RunLikelihoodDistance(scan, score.simulated, options.distance);
  return score;
}

}  // namespace scanloc
