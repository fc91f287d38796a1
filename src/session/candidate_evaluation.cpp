#include "scanloc/session/candidate_evaluation.hpp"

namespace scanloc {

CandidateEvaluationResult EvaluateCandidates(const MapView& map, const LaserScan& scan,
                                             const std::vector<Candidate>& candidates,
                                             const LaserMounting& mounting,
                                             const ScoringOptions& scoring,
                                             const ValidationOptions& validation) {
  scan.CheckConsistent();
  CandidateEvaluationResult result;
  if (map.empty()) result.problems.push_back("the map is empty");
  if (scan.CountValid() == 0) result.problems.push_back("the scan has no valid range");
  if (candidates.empty()) result.problems.push_back("no candidate posture was given");

  std::vector<LikelihoodTestResult> tests;
  for (const auto& candidate : candidates) {
    CandidateEvaluation e;
    e.candidate = candidate;
    e.T_world_laser = mounting.LaserPose(candidate.T_world_robot);
    const PostureScore score = ScorePosture(map, scan, e.T_world_laser, scoring);
    e.test = score.test;
    e.distance = score.distance;
    tests.push_back(score.test);
    result.candidates.push_back(e);
  }
  result.best = RankInto(tests, validation, result.candidates);
  if (!candidates.empty() && result.best < 0)
    result.problems.push_back("no candidate passed the validation rules");
  return result;
}

}  // namespace scanloc
