#include "scanloc/io/candidate_report.hpp"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <ostream>

namespace scanloc {

void PrintCandidateTable(std::ostream& out, const CandidateEvaluationResult& result) {
  char line[256];
  std::snprintf(line, sizeof line, "%-8s %9s %9s %10s %6s %6s %8s %11s %8s %8s %-5s %s\n", "posture",
                "x [m]", "y [m]", "θ [rad]", "MP", "NVP", "EV [m]", "√Disp [m]", "cost", "LD-EV",
                "valid", "reason");
  out << line;
  for (const auto& c : result.candidates) {
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
  if (result.best >= 0)
    out << "best: " << result.candidates[result.best].candidate.label << '\n';
  for (const auto& problem : result.problems) out << "problem: " << problem << '\n';
}

nlohmann::json ToJson(const LikelihoodTestResult& t) {
  return {{"valid_pairs", t.valid_pairs},       {"match_pairs", t.match_pairs},
          {"match_ratio", t.MatchRatio()},      {"expect_value_m", t.expect_value_m},
          {"dispersion_m2", t.dispersion_m2},   {"sqrt_dispersion_m", std::sqrt(t.dispersion_m2)},
          {"histogram", t.histogram}};
}

nlohmann::json ToJson(const LikelihoodDistanceResult& d) {
  return {{"valid_pairs", d.valid_pairs},
          {"weighted_pairs", d.weighted_pairs},
          {"expect_value_m", d.expect_value_m},
          {"dispersion_m2", d.dispersion_m2},
          {"cost_m2", d.cost_m2}};
}

nlohmann::json ToJson(const Pose2D& p) {
  return {{"x_m", p.x_m}, {"y_m", p.y_m}, {"yaw_rad", p.yaw_rad}};
}

nlohmann::json ToJson(const CandidateEvaluationResult& result) {
  nlohmann::json candidates = nlohmann::json::array();
  for (const auto& c : result.candidates)
    candidates.push_back({{"label", c.candidate.label},
                          {"T_world_robot", ToJson(c.candidate.T_world_robot)},
                          {"T_world_laser", ToJson(c.T_world_laser)},
                          {"likelihood_test", ToJson(c.test)},
                          {"likelihood_distance", ToJson(c.distance)},
                          {"cost", c.cost},
                          {"valid", c.verdict == Verdict::kValid},
                          {"reason", ToString(c.verdict)},
                          {"rank", c.rank}});
  return {{"candidates", candidates},
          {"best", result.best >= 0 ? nlohmann::json(result.candidates[result.best].candidate.label)
                                    : nlohmann::json(nullptr)},
          {"problems", result.problems}};
}

}  // namespace scanloc
