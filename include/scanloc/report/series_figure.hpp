#pragma once
// The moments over the session: for every localised iteration, the expected value and the match
// ratio of the posture it was refined to, against the thresholds of rules 1 and 2. Where the
// session struggles shows as a run of red points.

#include <string>
#include <vector>

#include "scanloc/likelihood/candidate_ranking.hpp"
#include "scanloc/report/run_records.hpp"

namespace scanloc {

// `id` must be unique in the page.
std::string MomentSeriesFigure(const std::vector<IterationRow>& rows,
                               const ValidationOptions& validation, const std::string& id);

// The Likelihood Test of the posture an iteration kept: after refinement when there was one,
// else the chosen candidate's; nullptr when the iteration was not localised.
const LikelihoodTestResult* FinalTest(const IterationRow& row);

}  // namespace scanloc
