#pragma once
// Refines every candidate posture, then validates and ranks the refined postures by the rules:
// the chapter's Approximate Localisation tables (2, 5, 6, 8).

#include <vector>

#include "scanloc/likelihood/candidate_ranking.hpp"
#include "scanloc/refinement/refiner.hpp"
#include "scanloc/session/candidate.hpp"

namespace scanloc {

struct RefinedCandidate {
  Candidate candidate;   // as given
  Pose2D T_world_robot;  // refined
  RefinementResult refinement;
  double cost = 0.0;  // (3.11) after refinement
  Verdict verdict = Verdict::kValid;
  int rank = -1;
};

struct CandidateRefinementResult {
  std::vector<RefinedCandidate> candidates;
  int best = -1;
};

CandidateRefinementResult RefineCandidates(const MapView& map, const LaserScan& scan,
                                           const std::vector<Candidate>& candidates,
                                           const LaserMounting& mounting,
                                           const ScoringOptions& scoring,
                                           const ValidationOptions& validation,
                                           const RefinerOptions& refiner);

}  // namespace scanloc
