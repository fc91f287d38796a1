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

  std::vector<Pose2D> postures;
  for (const auto& candidate : candidates)
    postures.push_back(mounting.LaserPose(candidate.T_world_robot));
  const std::vector<PostureScore> scores = ScorePostures(map, scan, postures, scoring);
  std::vector<LikelihoodTestResult> tests;
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    CandidateEvaluation e;
    e.candidate = candidates[i];
    e.T_world_laser = postures[i];
    e.test = scores[i].test;
    e.distance = scores[i].distance;
    tests.push_back(scores[i].test);
    result.candidates.push_back(e);
  }
  result.best = RankInto(tests, validation, result.candidates);
  if (!candidates.empty() && result.best < 0)
    result.problems.push_back("no candidate passed the validation rules");
  return result;
}

}  // namespace scanloc
