#pragma once
// Among a scan's valid refinements, the one that matched more of the scan at a lower truncated
// mean distance, where the rules preferred one that pushed pairs beyond T_Map.
//
// Rules 4 and 5 leave most choices among valid refinements to the cost (3.11), EV + α·(NVP −
// MP)/NVP. A posture that pushes a pair at distance d beyond T_Map lowers the cost whenever d > EV
// + α × match ratio (0.19 m at EV 0.15 m and half the scan matched): a refinement turned 5° off
// that keeps only its tight pairs beats the right posture that also keeps the loose ones.
// Acapulco's noisy scan 296 was kept −4.3° off at match ratio 0.37 (EV 0.098 m) where the
// prediction's refinement, 1.0° off, matched 0.74 (EV 0.147 m), and every relation across it was up
// to 4.4 m off. The truncated mean distance (hypothesis_evidence.hpp) charges each pair pushed out
// T_Map and never rewards losing one; the session keeps a valid refinement that matched more pairs
// than the rules' best and is lower by it, when the rules' best matched fewer pairs than the
// overlap fraction (the correction gate's, 0.75) of its: where two refinements match nearly as many
// pairs, they lie a fraction of a degree apart and the truncated mean judges them no better than
// (3.11) (docs/BENCHMARKS.md, "A refinement that matched more, at a lower truncated mean").

#include "scanloc/session/localisation.hpp"

namespace scanloc {

// The index in result.refined of the valid refinement with the lowest truncated mean distance
// among those the rules' best matched fewer pairs than overlap_fraction of, and lower than the
// rules' best by that mean; -1 when there is none (or no valid refinement).
int TighterRefinement(const LocalisationResult& result, double match_threshold_m,
                      double overlap_fraction);

// Keeps TighterRefinement's choice when there is one: it takes rank 0 and becomes the best and the
// kept refinement, the others valid keep their order after it. Returns the index of the
// refinement the rules had ranked first, or -1 when nothing changed.
int KeepTighterRefinement(LocalisationResult& result, double match_threshold_m,
                          double overlap_fraction);

}  // namespace scanloc
