#include "scanloc/session/tighter_refinement.hpp"

#include "scanloc/session/hypothesis_evidence.hpp"

namespace scanloc {

int TighterRefinement(const LocalisationResult& result, double match_threshold_m,
                      double overlap_fraction) {
  if (result.best_refined < 0) return -1;
  const RankedCandidate& best = result.refined[result.best_refined];
  double lowest = TruncatedMeanDistance(best.test, match_threshold_m);
  int tighter = -1;
  for (std::size_t i = 0; i < result.refined.size(); ++i) {
    const RankedCandidate& other = result.refined[i];
    if (other.rank < 0 || !(best.test.match_pairs < overlap_fraction * other.test.match_pairs))
      continue;
    const double mean = TruncatedMeanDistance(other.test, match_threshold_m);
    if (mean < lowest) {
      lowest = mean;
      tighter = static_cast<int>(i);
    }
  }
  return tighter;
}

int KeepTighterRefinement(LocalisationResult& result, double match_threshold_m,
                          double overlap_fraction) {
  const int tighter = TighterRefinement(result, match_threshold_m, overlap_fraction);
  if (tighter < 0) return -1;
  const int outranked = result.best_refined;
  const int rank = result.refined[tighter].rank;
  for (RankedCandidate& refined : result.refined)
    if (refined.rank >= 0 && refined.rank < rank) ++refined.rank;
  result.refined[tighter].rank = 0;
  result.best_refined = tighter;
  result.kept = tighter;
  return outranked;
}

}  // namespace scanloc
