#pragma once
// §3.3 validation rules 1–5: accept, reject and rank candidate postures by their Likelihood Tests.

#include <string>
#include <vector>

#include "scanloc/likelihood/likelihood_test.hpp"

namespace scanloc {

struct ValidationOptions {
  double min_match_ratio = 0.3;  // rule 1: MatchPairs/NVP must exceed this (0.2 in the factory)
  // Rule 2's E_max: ExpectValue must stay below it, metres. The chapter's 0.05 m suits its 0.15°
  // laser; on the 1° and 0.5° benchmark logs the refined EV has a median of 0.06–0.07 m, while a
  // heading 5° off scores 0.15–0.25 m.
  double max_expect_value_m = 0.1;
  double alpha_m = 0.1;         // (3.11) α: the cost charged per unit ratio of non-match pairs
  double max_cost_ratio = 1.5;  // rule 3: rejected when cost > max_cost_ratio · best cost
  // Rules 4 and 5: "a << b" reads as much_less_factor · a < b.
  double much_less_factor = 3.0;
  // Throws std::invalid_argument naming the first option out of its domain.
  void Validate() const;
};

enum class Verdict {
  kValid,
  kNoValidPairs,     // nothing to compare: empty map view or all-invalid scan
  kLowMatchRatio,    // rule 1
  kHighExpectValue,  // rule 2
  kHighCost,         // rule 3
};
const char* ToString(Verdict verdict);

struct CandidateAssessment {
  LikelihoodTestResult test;
  double cost = 0.0;  // (3.11)
  Verdict verdict = Verdict::kValid;
  int rank = -1;  // 0 for the best valid candidate; -1 when not valid
};

struct CandidateRanking {
  std::vector<CandidateAssessment> candidates;  // in input order
  std::vector<int> valid_order;                 // indices of valid candidates, best first
  int best = -1;                                // index of the best, -1 when none is valid
};

// (3.11) cost = ExpectValue + α · (NVP − MatchPairs) / NVP.
double LikelihoodCost(const LikelihoodTestResult& test, double alpha_m);

// True when candidate a is preferred to b by rules 4 and 5 (falling back to the cost, then the
// dispersion).
bool Preferred(const CandidateAssessment& a, const CandidateAssessment& b,
               const ValidationOptions& options);

// `max_expect_values_m`, when given, holds rule 2's E_max of each test (0: the options' bound).
CandidateRanking RankCandidates(const std::vector<LikelihoodTestResult>& tests,
                                const ValidationOptions& options = {},
                                const std::vector<double>& max_expect_values_m = {});

}  // namespace scanloc
