#include "scanloc/session/localisation.hpp"

#include <algorithm>
#include <chrono>
#include <limits>

namespace scanloc {
namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

// Ranks `ranked` by the rules on their tests, in place; returns the index of the best valid one.
int RankByRules(std::vector<RankedCandidate>& ranked, const ValidationOptions& validation) {
  std::vector<LikelihoodTestResult> tests;
  std::vector<double> bounds;  // each candidate's own E_max, when one has one
  tests.reserve(ranked.size());
  for (const RankedCandidate& r : ranked) tests.push_back(r.test);
  if (std::any_of(ranked.begin(), ranked.end(),
                  [](const RankedCandidate& r) { return r.candidate.max_expect_value_m > 0.0; }))
    for (const RankedCandidate& r : ranked) bounds.push_back(r.candidate.max_expect_value_m);
  const CandidateRanking ranking = RankCandidates(tests, validation, bounds);
  for (std::size_t i = 0; i < ranked.size(); ++i) {
    ranked[i].cost = ranking.candidates[i].cost;
    ranked[i].verdict = ranking.candidates[i].verdict;
    ranked[i].rank = ranking.candidates[i].rank;
  }
  return ranking.best;
}

std::vector<RankedCandidate> Evaluate(const MapView& map, const LaserScan& scan,
                                      const std::vector<Candidate>& candidates,
                                      const LaserMounting& mounting,
                                      const ScoringOptions& scoring) {
  std::vector<Pose2D> postures;
  for (const Candidate& candidate : candidates)
    postures.push_back(mounting.LaserPose(candidate.T_world_robot));
  const std::vector<PostureScore> scores = ScorePostures(map, scan, postures, scoring);
  std::vector<RankedCandidate> evaluated(candidates.size());
  for (std::size_t i = 0; i < candidates.size(); ++i) {
    evaluated[i].candidate = candidates[i];
    evaluated[i].T_world_robot = candidates[i].T_world_robot;
    evaluated[i].T_world_laser = postures[i];
    evaluated[i].test = scores[i].test;
    evaluated[i].distance = scores[i].distance;
  }
  return evaluated;
}

// The index of the lowest cost (3.11), the first on ties; -1 when none is finite.
int Cheapest(const std::vector<RankedCandidate>& ranked) {
  int cheapest = -1;
  double best_cost = std::numeric_limits<double>::infinity();
  for (std::size_t i = 0; i < ranked.size(); ++i)
    if (ranked[i].cost < best_cost) {
      best_cost = ranked[i].cost;
      cheapest = static_cast<int>(i);
    }
  return cheapest;
}

// The evaluated candidates to refine, in the order they are refined. kBestValidAndFirst adds the
// first candidate (the prediction) when the rules rejected it as given: its refinement is ranked
// with the others and, when none passes, is one more guess the cheapest of is kept.
std::vector<int> ToRefine(const std::vector<RankedCandidate>& evaluated, RefinePolicy policy,
                          int max_refined) {
  std::vector<int> order;
  if (policy == RefinePolicy::kNone) return order;
  for (std::size_t i = 0; i < evaluated.size(); ++i)
    if (policy == RefinePolicy::kAll || evaluated[i].rank >= 0)
      order.push_back(static_cast<int>(i));
  if (policy != RefinePolicy::kAll) {
    std::sort(order.begin(), order.end(),
              [&](int a, int b) { return evaluated[a].rank < evaluated[b].rank; });
    if (static_cast<int>(order.size()) > max_refined) order.resize(std::max(0, max_refined));
    // None valid: the cheapest by (3.11) alone is the best guess to refine.
    if (policy != RefinePolicy::kValidOnly && order.empty() && !evaluated.empty())
      order.push_back(std::max(0, Cheapest(evaluated)));
  }
  if (policy == RefinePolicy::kBestValidAndFirst && !evaluated.empty() &&
      std::find(order.begin(), order.end(), 0) == order.end())
    order.push_back(0);
  return order;
}

RankedCandidate RefineOne(const MapView& map, const LaserScan& scan, const RankedCandidate& from,
                          int index, const LaserMounting& mounting,
                          const LocalisationOptions& options) {
  RefinerOptions refiner = options.refiner;
  refiner.ceres.score_initial = false;  // the evaluation scored the candidate already
  RankedCandidate refined;
  refined.candidate = from.candidate;
  refined.from = index;
  refined.refinement =
      Refine(map, scan, from.T_world_laser, options.scoring, options.validation.alpha_m, refiner);
  RefinementResult& result = *refined.refinement;
  result.test_before = from.test;
  result.distance_before = from.distance;
  refined.T_world_laser = result.T_world_laser;
  refined.T_world_robot = mounting.RobotPose(result.T_world_laser);
  refined.test = result.test_after;
  refined.distance = result.distance_after;
  return refined;
}

}  // namespace

LocalisationResult Localise(const MapView& map, const LaserScan& scan,
                            const std::vector<Candidate>& candidates, const LaserMounting& mounting,
                            const LocalisationOptions& options, RefinePolicy policy,
                            int max_refined) {
  scan.CheckConsistent();
  options.validation.Validate();
  LocalisationResult result;
  if (map.empty()) result.problems.push_back("the map is empty");
  if (scan.CountValid() == 0) result.problems.push_back("the scan has no valid range");
  if (candidates.empty()) result.problems.push_back("no candidate posture was given");

  const auto evaluate_start = std::chrono::steady_clock::now();
  result.evaluated = Evaluate(map, scan, candidates, mounting, options.scoring);
  result.best_evaluated = RankByRules(result.evaluated, options.validation);
  if (!candidates.empty() && result.best_evaluated < 0)
    result.problems.push_back("no candidate passed the validation rules");
  result.evaluate_s = SecondsSince(evaluate_start);

  const auto refine_start = std::chrono::steady_clock::now();
  for (const int i : ToRefine(result.evaluated, policy, max_refined))
    result.refined.push_back(RefineOne(map, scan, result.evaluated[i], i, mounting, options));
  if (!result.refined.empty()) {
    result.best_refined = RankByRules(result.refined, options.validation);
    // None passes: the cheapest refinement is the flagged guess kept.
    result.kept =
        result.best_refined >= 0 ? result.best_refined : std::max(0, Cheapest(result.refined));
  }
  result.refine_s = SecondsSince(refine_start);
  return result;
}

}  // namespace scanloc
