#pragma once
// The operator's view of a candidate evaluation: the chapter's table, and JSON with histograms.

#include <iosfwd>
#include <nlohmann/json_fwd.hpp>

#include "scanloc/session/candidate_evaluation.hpp"
#include "scanloc/session/candidate_refinement.hpp"

namespace scanloc {

// One row per candidate: x, y, θ, MP, NVP, EV, √Disp, cost, Likelihood Distance EV, valid, reason.
void PrintCandidateTable(std::ostream& out, const CandidateEvaluationResult& result);

// Before and after refinement, with the correction in mm and mrad (Tables 2, 5, 6 and 8).
void PrintRefinementTable(std::ostream& out, const CandidateRefinementResult& result);

nlohmann::json ToJson(const LikelihoodTestResult& test);
nlohmann::json ToJson(const RefinementResult& refinement);
nlohmann::json ToJson(const CandidateRefinementResult& result);
nlohmann::json ToJson(const LikelihoodDistanceResult& distance);
nlohmann::json ToJson(const Pose2D& pose);
nlohmann::json ToJson(const CandidateEvaluationResult& result);

}  // namespace scanloc
