#include "scanloc/session/candidate_refinement.hpp"

namespace scanloc {

CandidateRefinementResult RefineCandidates(const MapView& map, const LaserScan& scan,
                                           const std::vector<Candidate>& candidates,
                                           const LaserMounting& mounting,
                                           const ScoringOptions& scoring,
                                           const ValidationOptions& validation,
                                           const RefinerOptions& refiner) {
  CandidateRefinementResult result;
  std::vector<LikelihoodTestResult> tests;
  for (const auto& candidate : candidates) {
    RefinedCandidate refined;
    refined.candidate = candidate;
    refined.refinement = Refine(map, scan, mounting.LaserPose(candidate.T_world_robot), scoring,
                                validation.alpha_m, refiner);
    refined.T_world_robot = mounting.RobotPose(refined.refinement.T_world_laser);
    tests.push_back(refined.refinement.test_after);
    result.candidates.push_back(refined);
  }
  result.best = RankInto(tests, validation, result.candidates);
  return result;
}

}  // namespace scanloc
