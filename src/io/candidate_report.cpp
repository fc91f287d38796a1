#include "scanloc/io/candidate_report.hpp"

#include <cmath>
#include <cstdio>
#include <nlohmann/json.hpp>
#include <ostream>
#include <string>
#include <utility>

#include "scanloc/io/json_writer.hpp"
#include "scanloc/io/record_keys.hpp"

namespace scanloc {
namespace keys = record_keys;

namespace {

template <class Write>
nlohmann::json Parsed(const Write& write) {
  std::string text;
  JsonWriter out(text);
  write(out);
  return nlohmann::json::parse(text);
}

void WriteCorrection(JsonWriter& out, const Pose2D& from, const Pose2D& to) {
  out.BeginArray();
  out.Value(1e3 * (to.x_m - from.x_m));
  out.Value(1e3 * (to.y_m - from.y_m));
  out.Value(1e3 * NormalizeAngle(to.yaw_rad - from.yaw_rad));
  out.EndArray();
}

// "best": the best one's label, or null.
void WriteBestLabel(JsonWriter& out, const std::vector<RankedCandidate>& ranked, int best) {
  out.Key(keys::kBest);
  if (best >= 0)
    out.Value(ranked[best].candidate.label);
  else
    out.Null();
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

// Each object is written once, by its writer; the nlohmann values of the commands' reports are
// that text parsed (json_writer.hpp: the writer orders the members as dump() does).

void WriteJson(JsonWriter& out, const LikelihoodTestResult& t) {
  out.BeginObject();
  out.Member(keys::kValidPairs, t.valid_pairs);
  out.Member(keys::kMatchPairs, t.match_pairs);
  out.Member(keys::kMatchRatio, t.MatchRatio());
  out.Member(keys::kExpectValueM, t.expect_value_m);
  out.Member(keys::kDispersionM2, t.dispersion_m2);
  out.Member(keys::kSqrtDispersionM, std::sqrt(t.dispersion_m2));
  out.Member(keys::kHistogram, t.histogram);
  out.EndObject();
}

void WriteJson(JsonWriter& out, const LikelihoodDistanceResult& d) {
  out.BeginObject();
  out.Member(keys::kValidPairs, d.valid_pairs);
  out.Member(keys::kWeightedPairs, d.weighted_pairs);
  out.Member(keys::kExpectValueM, d.expect_value_m);
  out.Member(keys::kDispersionM2, d.dispersion_m2);
  out.Member(keys::kCostM2, d.cost_m2);
  out.EndObject();
}

void WriteJson(JsonWriter& out, const Pose2D& p) {
  out.BeginObject();
  out.Member(keys::kXM, p.x_m);
  out.Member(keys::kYM, p.y_m);
  out.Member(keys::kYawRad, p.yaw_rad);
  out.EndObject();
}

void WriteJson(JsonWriter& out, const RefinementResult& r) {
  out.BeginObject();
  out.Key(keys::kTWorldLaser);
  WriteJson(out, r.T_world_laser);
  out.Member(keys::kConverged, r.converged);
  out.Member(keys::kIterations, r.iterations);
  out.Key(keys::kLikelihoodTestBefore);
  WriteJson(out, r.test_before);
  out.Key(keys::kLikelihoodTestAfter);
  WriteJson(out, r.test_after);
  out.Key(keys::kLikelihoodDistanceBefore);
  WriteJson(out, r.distance_before);
  out.Key(keys::kLikelihoodDistanceAfter);
  WriteJson(out, r.distance_after);
  out.Member(keys::kDegenerate, r.degenerate);
  out.Member(keys::kDegeneracy, r.degeneracy);
  out.Member(keys::kTimeS, r.time_s);
  if (r.has_covariance) {
    out.Key(keys::kCovariance);
    out.BeginArray();
    for (int i = 0; i < 3; ++i) {
      out.BeginArray();
      for (int j = 0; j < 3; ++j) out.Value(r.covariance(i, j));
      out.EndArray();
    }
    out.EndArray();
  }
  out.EndObject();
}

void WriteEvaluatedCandidates(JsonWriter& out, const LocalisationResult& result) {
  out.BeginArray();
  for (const auto& c : result.evaluated) {
    out.BeginObject();
    out.Member(keys::kLabel, c.candidate.label);
    out.Key(keys::kTWorldRobot);
    WriteJson(out, c.candidate.T_world_robot);
    out.Key(keys::kTWorldLaser);
    WriteJson(out, c.T_world_laser);
    out.Key(keys::kLikelihoodTest);
    WriteJson(out, c.test);
    out.Key(keys::kLikelihoodDistance);
    WriteJson(out, c.distance);
    out.Member(keys::kCost, c.cost);
    out.Member(keys::kValid, c.verdict == Verdict::kValid);
    out.Member(keys::kReason, ToString(c.verdict));
    out.Member(keys::kRank, c.rank);
    out.EndObject();
  }
  out.EndArray();
}

nlohmann::json ToJson(const LikelihoodTestResult& t) {
  return Parsed([&](JsonWriter& out) { WriteJson(out, t); });
}

nlohmann::json ToJson(const LikelihoodDistanceResult& d) {
  return Parsed([&](JsonWriter& out) { WriteJson(out, d); });
}

nlohmann::json ToJson(const Pose2D& p) {
  return Parsed([&](JsonWriter& out) { WriteJson(out, p); });
}

nlohmann::json ToJson(const RefinementResult& r) {
  return Parsed([&](JsonWriter& out) { WriteJson(out, r); });
}

nlohmann::json RefinedToJson(const LocalisationResult& result) {
  return Parsed([&](JsonWriter& out) {
    out.BeginObject();
    out.Key(keys::kCandidates);
    out.BeginArray();
    for (const auto& c : result.refined) {
      const Pose2D& a = c.candidate.T_world_robot;
      const Pose2D& b = c.T_world_robot;
      out.BeginObject();
      out.Member(keys::kLabel, c.candidate.label);
      out.Key(keys::kInitialTWorldRobot);
      WriteJson(out, a);
      out.Key(keys::kRefinedTWorldRobot);
      WriteJson(out, b);
      out.Key(keys::kCorrectionMmMmMrad);
      WriteCorrection(out, a, b);
      out.Key(keys::kRefinement);
      WriteJson(out, *c.refinement);
      out.Member(keys::kCost, c.cost);
      out.Member(keys::kValid, c.verdict == Verdict::kValid);
      out.Member(keys::kReason, ToString(c.verdict));
      out.Member(keys::kRank, c.rank);
      out.EndObject();
    }
    out.EndArray();
    WriteBestLabel(out, result.refined, result.best_refined);
    out.EndObject();
  });
}

nlohmann::json EvaluatedToJson(const LocalisationResult& result) {
  return Parsed([&](JsonWriter& out) {
    out.BeginObject();
    out.Key(keys::kCandidates);
    WriteEvaluatedCandidates(out, result);
    WriteBestLabel(out, result.evaluated, result.best_evaluated);
    out.Member(keys::kProblems, result.problems);
    out.EndObject();
  });
}

}  // namespace scanloc
