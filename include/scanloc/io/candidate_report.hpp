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

class JsonWriter;

// The objects of the iteration records and of the reports, each written once (the nlohmann
// values below are their text, parsed).
void WriteJson(JsonWriter& out, const LikelihoodTestResult& test);
void WriteJson(JsonWriter& out, const LikelihoodDistanceResult& distance);
void WriteJson(JsonWriter& out, const Pose2D& pose);
void WriteJson(JsonWriter& out, const RefinementResult& refinement);
// The candidates as given with their tests: EvaluatedToJson's "candidates".
void WriteEvaluatedCandidates(JsonWriter& out, const LocalisationResult& result);

nlohmann::json ToJson(const LikelihoodTestResult& test);
nlohmann::json ToJson(const RefinementResult& refinement);
// {"candidates": the refinements, each before and after, "best"}.
nlohmann::json RefinedToJson(const LocalisationResult& result);
nlohmann::json ToJson(const LikelihoodDistanceResult& distance);
nlohmann::json ToJson(const Pose2D& pose);
// {"candidates": the candidates as given with their tests, "best", "problems"}.
nlohmann::json EvaluatedToJson(const LocalisationResult& result);

}  // namespace scanloc
