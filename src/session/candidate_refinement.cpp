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
    refined.refinement =
        Refine(map, scan, mounting.LaserPose(candidate.T_world_robot), scoring, refiner);
    refined.T_world_robot = mounting.RobotPose(refined.refinement.T_world_laser);
    tests.push_back(refined.refinement.test_after);
    result.candidates.push_back(refined);
  }
  const CandidateRanking ranking = RankCandidates(tests, validation);
  for (std::size_t i = 0; i < result.candidates.size(); ++i) {
    result.candidates[i].cost = ranking.candidates[i].cost;
    result.candidates[i].verdict = ranking.candidates[i].verdict;
    result.candidates[i].rank = ranking.candidates[i].rank;
  }
  result.best = ranking.best;
  return result;
}

}  // namespace scanloc
