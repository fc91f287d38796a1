#pragma once
// The operator's view of a candidate evaluation: the chapter's table, and JSON with histograms.

#include <iosfwd>
#include <nlohmann/json_fwd.hpp>

#include "scanloc/session/localisation.hpp"

namespace scanloc {

// One row per candidate: x, y, θ, MP, NVP, EV, √Disp, cost, Likelihood Distance EV, valid, reason.
// The candidates as given (result.evaluated), with the best and the problems.
void PrintCandidateTable(std::ostream& out, const LocalisationResult& result);

// Before and after refinement, with the correction in mm and mrad (Tables 2, 5, 6 and 8).
// The refinements (result.refined).
void PrintRefinementTable(std::ostream& out, const LocalisationResult& result);

nlohmann::json ToJson(const LikelihoodTestResult& test);
nlohmann::json ToJson(const RefinementResult& refinement);
// {"candidates": the refinements, each before and after, "best"}.
nlohmann::json RefinedToJson(const LocalisationResult& result);
nlohmann::json ToJson(const LikelihoodDistanceResult& distance);
nlohmann::json ToJson(const Pose2D& pose);
// {"candidates": the candidates as given with their tests, "best", "problems"}.
nlohmann::json EvaluatedToJson(const LocalisationResult& result);

}  // namespace scanloc
