#include "scanloc/io/candidate_report.hpp"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <ostream>
#include <utility>
#include "scanloc/io/record_keys.hpp"

namespace scanloc {
namespace keys = record_keys;

namespace {

// The best one's label, or null.
nlohmann::json BestLabel(const std::vector<RankedCandidate>& ranked, int best) {
  return best >= 0 ? nlohmann::json(ranked[best].candidate.label) : nlohmann::json(nullptr);
}

}  // namespace

void PrintCandidateTable(std::ostream& out, const LocalisationResult& result) {
  char line[256];
  std::snprintf(line, sizeof line, "%-8s %9s %9s %10s %6s %6s %8s %11s %8s %8s %-5s %s\n",
                "posture", "x [m]", "y [m]", "θ [rad]", "MP", "NVP", "EV [m]", "√Disp [m]", "cost",
                "LD-EV", "valid", "reason");
  out << line;
  for (const auto& c : result.evaluated) {
    const Pose2D& p = c.candidate.T_world_robot;
    std::snprintf(line, sizeof line,
                  "%-8s %9.4f %9.4f %9.5f %6d %6d %8.5f %9.5f %8.5f %8.5f %-5s %s\n",
                  c.candidate.label.c_str(), p.x_m, p.y_m, p.yaw_rad, c.test.match_pairs,
                  c.test.valid_pairs, c.test.expect_value_m, std::sqrt(c.test.dispersion_m2),
                  c.cost, c.distance.expect_value_m, c.verdict == Verdict::kValid ? "yes" : "no",
                  c.verdict == Verdict::kValid ? ("rank " + std::to_string(c.rank)).c_str()
                                               : ToString(c.verdict));
    out << line;
  }
  if (result.best_evaluated >= 0)
    out << "best: " << result.evaluated[result.best_evaluated].candidate.label << '\n';
  for (const auto& problem : result.problems) out << "problem: " << problem << '\n';
}

void PrintRefinementTable(std::ostream& out, const LocalisationResult& result) {
  char line[320];
  std::snprintf(line, sizeof line,
                "%-8s %-6s %9s %9s %10s %27s %13s %19s %11s %8s %6s %8s %-5s %s\n", "posture",
                "stage", "x [m]", "y [m]", "θ [rad]", "correction [mm, mm, mrad]", "MP", "EV [m]",
                "√Disp [m]", "LD-EV", "iters", "time[ms]", "valid", "reason");
  out << line;
  for (const auto& c : result.refined) {
    const Pose2D& a = c.candidate.T_world_robot;
    const Pose2D& b = c.T_world_robot;
    const RefinementResult& r = *c.refinement;
    std::snprintf(line, sizeof line, "%-8s %-6s %9.4f %9.4f %9.5f %26s %6d %8.5f %9.5f %8.5f\n",
                  c.candidate.label.c_str(), "before", a.x_m, a.y_m, a.yaw_rad, "",
                  r.test_before.match_pairs, r.test_before.expect_value_m,
                  std::sqrt(r.test_before.dispersion_m2), r.distance_before.expect_value_m);
    out << line;
    std::string reason =
        c.verdict == Verdict::kValid ? "rank " + std::to_string(c.rank) : ToString(c.verdict);
    if (!r.converged) reason += "; not converged";
    if (r.degenerate) reason += "; degenerate: " + r.degeneracy;
    std::snprintf(line, sizeof line,
                  "%-8s %-6s %9.4f %9.4f %9.5f %8.1f %8.1f %8.2f %6d %8.5f %9.5f %8.5f %6d %8.2f "
                  "%-5s %s\n",
                  "", "after", b.x_m, b.y_m, b.yaw_rad, 1e3 * (b.x_m - a.x_m),
                  1e3 * (b.y_m - a.y_m), 1e3 * NormalizeAngle(b.yaw_rad - a.yaw_rad),
                  r.test_after.match_pairs, r.test_after.expect_value_m,
                  std::sqrt(r.test_after.dispersion_m2), r.distance_after.expect_value_m,
                  r.iterations, 1e3 * r.time_s, c.verdict == Verdict::kValid ? "yes" : "no",
                  reason.c_str());
    out << line;
  }
  if (result.best_refined >= 0)
    out << "best: " << result.refined[result.best_refined].candidate.label << '\n';
  else
    out << "problem: no refined candidate passed the validation rules\n";
}

// The objects of every record are built member by member: nlohmann's initializer lists build
// a two-element array per member first (twice the time, a scan's record after record).

nlohmann::json ToJson(const LikelihoodTestResult& t) {
  nlohmann::json out = nlohmann::json::object();
  out[keys::kValidPairs] = t.valid_pairs;
  out[keys::kMatchPairs] = t.match_pairs;
  out[keys::kMatchRatio] = t.MatchRatio();
  out[keys::kExpectValueM] = t.expect_value_m;
  out[keys::kDispersionM2] = t.dispersion_m2;
  out[keys::kSqrtDispersionM] = std::sqrt(t.dispersion_m2);
  out[keys::kHistogram] = t.histogram;
  return out;
}

nlohmann::json ToJson(const LikelihoodDistanceResult& d) {
  nlohmann::json out = nlohmann::json::object();
  out[keys::kValidPairs] = d.valid_pairs;
  out[keys::kWeightedPairs] = d.weighted_pairs;
  out[keys::kExpectValueM] = d.expect_value_m;
  out[keys::kDispersionM2] = d.dispersion_m2;
  out[keys::kCostM2] = d.cost_m2;
  return out;
}

nlohmann::json ToJson(const Pose2D& p) {
  nlohmann::json out = nlohmann::json::object();
  out[keys::kXM] = p.x_m;
  out[keys::kYM] = p.y_m;
  out[keys::kYawRad] = p.yaw_rad;
  return out;
}

nlohmann::json ToJson(const RefinementResult& r) {
  nlohmann::json out = nlohmann::json::object();
  out[keys::kTWorldLaser] = ToJson(r.T_world_laser);
  out[keys::kConverged] = r.converged;
  out[keys::kIterations] = r.iterations;
  out[keys::kLikelihoodTestBefore] = ToJson(r.test_before);
  out[keys::kLikelihoodTestAfter] = ToJson(r.test_after);
  out[keys::kLikelihoodDistanceBefore] = ToJson(r.distance_before);
  out[keys::kLikelihoodDistanceAfter] = ToJson(r.distance_after);
  out[keys::kDegenerate] = r.degenerate;
  out[keys::kDegeneracy] = r.degeneracy;
  out[keys::kTimeS] = r.time_s;
  if (r.has_covariance) {
    nlohmann::json rows = nlohmann::json::array();
    for (int i = 0; i < 3; ++i)
      rows.push_back({r.covariance(i, 0), r.covariance(i, 1), r.covariance(i, 2)});
    out["covariance"] = rows;
  }
  return out;
}

nlohmann::json RefinedToJson(const LocalisationResult& result) {
  nlohmann::json candidates = nlohmann::json::array();
  for (const auto& c : result.refined) {
    const Pose2D& a = c.candidate.T_world_robot;
    const Pose2D& b = c.T_world_robot;
    candidates.push_back({{keys::kLabel, c.candidate.label},
                          {keys::kInitialTWorldRobot, ToJson(a)},
                          {keys::kRefinedTWorldRobot, ToJson(b)},
                          {keys::kCorrectionMmMmMrad,
                           {1e3 * (b.x_m - a.x_m), 1e3 * (b.y_m - a.y_m),
                            1e3 * NormalizeAngle(b.yaw_rad - a.yaw_rad)}},
                          {keys::kRefinement, ToJson(*c.refinement)},
                          {keys::kCost, c.cost},
                          {keys::kValid, c.verdict == Verdict::kValid},
                          {keys::kReason, ToString(c.verdict)},
                          {keys::kRank, c.rank}});
  }
  nlohmann::json out = nlohmann::json::object();
  out[keys::kCandidates] = std::move(candidates);  // moved: an initializer list would copy them
  out[keys::kBest] = BestLabel(result.refined, result.best_refined);
  return out;
}

nlohmann::json EvaluatedToJson(const LocalisationResult& result) {
  nlohmann::json candidates = nlohmann::json::array();
  for (const auto& c : result.evaluated) {
    nlohmann::json& candidate = candidates.emplace_back(nlohmann::json::object());
    candidate[keys::kLabel] = c.candidate.label;
    candidate[keys::kTWorldRobot] = ToJson(c.candidate.T_world_robot);
    candidate[keys::kTWorldLaser] = ToJson(c.T_world_laser);
    candidate[keys::kLikelihoodTest] = ToJson(c.test);
    candidate[keys::kLikelihoodDistance] = ToJson(c.distance);
    candidate[keys::kCost] = c.cost;
    candidate[keys::kValid] = c.verdict == Verdict::kValid;
    candidate[keys::kReason] = ToString(c.verdict);
    candidate[keys::kRank] = c.rank;
  }
  nlohmann::json out = nlohmann::json::object();
  out[keys::kCandidates] = std::move(candidates);  // moved: an initializer list would copy them
  out[keys::kBest] = BestLabel(result.evaluated, result.best_evaluated);
  out[keys::kProblems] = result.problems;
  return out;
}

}  // namespace scanloc
