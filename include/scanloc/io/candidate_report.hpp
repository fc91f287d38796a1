#pragma once
// The operator's view of a candidate evaluation: the chapter's table, and JSON with histograms.

#include <iosfwd>
#include <nlohmann/json_fwd.hpp>

#include "scanloc/session/candidate_evaluation.hpp"

namespace scanloc {

// One row per candidate: x, y, θ, MP, NVP, EV, √Disp, cost, Likelihood Distance EV, valid, reason.
void PrintCandidateTable(std::ostream& out, const CandidateEvaluationResult& result);

nlohmann::json ToJson(const LikelihoodTestResult& test);
nlohmann::json ToJson(const LikelihoodDistanceResult& distance);
nlohmann::json ToJson(const Pose2D& pose);
nlohmann::json ToJson(const CandidateEvaluationResult& result);

}  // namespace scanloc
