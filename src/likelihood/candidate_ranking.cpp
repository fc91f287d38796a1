#include "scanloc/likelihood/candidate_ranking.hpp"

#include <algorithm>
#include <cmath>
#include <numeric>
#include <stdexcept>

namespace scanloc {
namespace {

// Relative difference (a − b) / max(|a|, |b|); 0 when both are 0.
double Relative(double a, double b) {
  const double scale = std::max(std::abs(a), std::abs(b));
  return scale > 0.0 ? (a - b) / scale : 0.0;
}

void Require(bool condition, const char* message) {
  if (!condition) throw std::invalid_argument(std::string("ValidationOptions: ") + message);
}

}  // namespace

void ValidationOptions::Validate() const {
  Require(std::isfinite(min_match_ratio) && min_match_ratio >= 0.0 && min_match_ratio < 1.0,
          "min_match_ratio must be in [0, 1)");
  Require(std::isfinite(max_expect_value_m) && max_expect_value_m > 0.0,
          "max_expect_value_m (E_max) must be positive and finite");
  Require(std::isfinite(alpha_m) && alpha_m >= 0.0, "alpha_m must be finite and >= 0");
  Require(std::isfinite(max_cost_ratio) && max_cost_ratio >= 1.0,
          "max_cost_ratio must be finite and >= 1");
  Require(std::isfinite(much_less_factor) && much_less_factor >= 1.0,
          "much_less_factor must be finite and >= 1");
}

const char* ToString(Verdict verdict) {
  switch (verdict) {
    case Verdict::kValid:
      return "valid";
    case Verdict::kNoValidPairs:
      return "no valid pairs";
    case Verdict::kLowMatchRatio:
      return "rule 1: match ratio too low";
    case Verdict::kHighExpectValue:
      return "rule 2: expected value too high";
    case Verdict::kHighCost:
      return "rule 3: cost much higher than the best";
  }
  return "?";
}

double LikelihoodCost(const LikelihoodTestResult& test, double alpha_m) {
  if (test.valid_pairs == 0) return std::numeric_limits<double>::infinity();
  return test.expect_value_m +
         alpha_m * static_cast<double>(test.valid_pairs - test.match_pairs) / test.valid_pairs;
}

bool Preferred(const CandidateAssessment& a, const CandidateAssessment& b,
               const ValidationOptions& options) {
  const double f = options.much_less_factor;
  const double rel_mp = std::abs(Relative(a.test.match_pairs, b.test.match_pairs));
  const double rel_ev = std::abs(Relative(a.test.expect_value_m, b.test.expect_value_m));
  const double rel_disp = std::abs(Relative(a.test.dispersion_m2, b.test.dispersion_m2));
  // (3.12) rule 4: match pairs close compared with the expected values → the expected value decides
  if (f * rel_mp < rel_ev) {
    // (3.13) rule 5: expected values close compared with the dispersions → the dispersion decides
    if (f * rel_ev < rel_disp) return a.test.dispersion_m2 < b.test.dispersion_m2;
    return a.test.expect_value_m < b.test.expect_value_m;
  }
  if (f * rel_ev < rel_disp && f * rel_mp < rel_disp)
    return a.test.dispersion_m2 < b.test.dispersion_m2;
  // Otherwise the moments are weighed together: the cost (3.11), then the dispersion.
  if (a.cost != b.cost) return a.cost < b.cost;
  return a.test.dispersion_m2 < b.test.dispersion_m2;
}

CandidateRanking RankCandidates(const std::vector<LikelihoodTestResult>& tests,
                                const ValidationOptions& options,
                                const std::vector<double>& max_expect_values_m) {
  options.Validate();
  if (!max_expect_values_m.empty() && max_expect_values_m.size() != tests.size())
    throw std::invalid_argument("RankCandidates: one E_max per test, or none");
  CandidateRanking ranking;
  double best_cost = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < tests.size(); ++i) {
    const LikelihoodTestResult& test = tests[i];
    const double own = max_expect_values_m.empty() ? 0.0 : max_expect_values_m[i];
    const double max_expect_value_m = own > 0.0 ? own : options.max_expect_value_m;
    CandidateAssessment c;
    c.test = test;
    c.cost = LikelihoodCost(test, options.alpha_m);
    if (test.valid_pairs == 0) {
      c.verdict = Verdict::kNoValidPairs;
    } else if (!(test.MatchRatio() > options.min_match_ratio)) {  // rule 1
      c.verdict = Verdict::kLowMatchRatio;
    } else if (!(test.expect_value_m < max_expect_value_m)) {  // rule 2
      c.verdict = Verdict::kHighExpectValue;
    } else {
      best_cost = std::min(best_cost, c.cost);
    }
    ranking.candidates.push_back(c);
  }
  // Rule 3, against the best cost among the candidates that passed rules 1 and 2.
  for (auto& c : ranking.candidates)
    if (c.verdict == Verdict::kValid && c.cost > options.max_cost_ratio * best_cost)
      c.verdict = Verdict::kHighCost;

  std::vector<int>& order = ranking.valid_order;
  for (int i = 0; i < static_cast<int>(ranking.candidates.size()); ++i)
    if (ranking.candidates[i].verdict == Verdict::kValid) order.push_back(i);
  // Pairwise preferences need not be transitive, so rank by the number of pairwise wins
  // (ties by cost, then input order): a total order whatever the preferences.
  std::vector<int> wins(ranking.candidates.size(), 0);
  for (const int i : order)
    for (const int j : order)
      if (i != j && Preferred(ranking.candidates[i], ranking.candidates[j], options)) ++wins[i];
  std::stable_sort(order.begin(), order.end(), [&](int i, int j) {
    if (wins[i] != wins[j]) return wins[i] > wins[j];
    return ranking.candidates[i].cost < ranking.candidates[j].cost;
  });
  for (std::size_t r = 0; r < order.size(); ++r)
    ranking.candidates[order[r]].rank = static_cast<int>(r);
  if (!order.empty()) ranking.best = order.front();
  return ranking;
}

}  // namespace scanloc
