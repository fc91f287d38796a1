#pragma once
// Simulates, tests and ranks a set of candidate postures against one scan: the chapter's
// "Likelihood Test validation" of Tables 1, 3, 4, 7, ...

#include <string>
#include <vector>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/likelihood/candidate_ranking.hpp"
#include "scanloc/refinement/refinement.hpp"
#include "scanloc/session/candidate.hpp"

namespace scanloc {

struct CandidateEvaluation {
  Candidate candidate;
  Pose2D T_world_laser;
  LikelihoodTestResult test;
  LikelihoodDistanceResult distance;
  double cost = 0.0;  // (3.11)
  Verdict verdict = Verdict::kValid;
  int rank = -1;  // 0 for the best valid candidate, -1 when not valid
};

struct CandidateEvaluationResult {
  std::vector<CandidateEvaluation> candidates;  // input order
  int best = -1;                                // index of the best valid candidate, or -1
  // Degenerate data, said rather than hidden: "empty map", "scan has no valid range", ...
  std::vector<std::string> problems;
};

CandidateEvaluationResult EvaluateCandidates(const MapView& map, const LaserScan& scan,
                                             const std::vector<Candidate>& candidates,
                                             const LaserMounting& mounting,
                                             const ScoringOptions& scoring,
                                             const ValidationOptions& validation);

}  // namespace scanloc
