#include "evaluate_closures.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>
#include <set>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "evaluation_frame.hpp"
#include "scanloc/evaluation/closure_precision.hpp"
#include "scanloc/io/g2o_file.hpp"
#include "scanloc/io/trajectory.hpp"
#include "scanloc/report/run_records.hpp"

namespace scanloc::app {
namespace {

constexpr double kDegreesPerRadian = 180.0 / M_PI;

// What the run folder says about its closures.
struct RunClosures {
  std::size_t tried = 0;
  std::vector<const IterationRow*> rows;  // the measured closures' rows
  std::vector<ClosureMeasurement> measurements;
  bool graph_known = false;  // graph.g2o was there
};

// The closure edges (old node, node) of the run's graph.g2o, or nothing when it has none.
std::optional<std::set<std::pair<std::size_t, std::size_t>>> GraphEdges(
    const std::filesystem::path& folder) {
  const std::filesystem::path path = folder / "graph.g2o";
  if (!std::filesystem::exists(path)) return std::nullopt;
  std::set<std::pair<std::size_t, std::size_t>> edges;
  const PoseGraph graph = ReadG2o(path.string());
  for (const PoseGraphEdge& edge : graph.edges()) edges.insert({edge.from, edge.to});
  return edges;
}

RunClosures ReadRunClosures(const std::filesystem::path& folder, const IterationRows& records) {
  const std::string records_path = (folder / "iterations.jsonl").string();
  const auto graph = GraphEdges(folder);
  RunClosures run;
  run.graph_known = graph.has_value();
  for (const IterationRow& row : records.rows) {
    if (!row.closure) continue;
    ++run.tried;
    const ClosureRow& closure = *row.closure;
    if (!closure.T_old_robot) continue;
    if (closure.old_iteration >= records.rows.size())
      throw std::runtime_error(records_path + ": record " + std::to_string(row.index) +
                               " closed with record " + std::to_string(closure.old_iteration) +
                               ", which the run does not have");
    ClosureMeasurement measurement;
    measurement.t_old_s = records.rows[closure.old_iteration].timestamp_s;
    measurement.t_s = row.timestamp_s;
    measurement.T_old_robot = *closure.T_old_robot;
    measurement.accepted = closure.accepted;
    measurement.in_graph = graph && graph->count({closure.old_node, closure.node}) > 0;
    run.rows.push_back(&row);
    run.measurements.push_back(measurement);
  }
  if (run.tried == 0)
    throw std::runtime_error(records_path +
                             ": no loop closure was tried (was the session run with "
                             "loop_closure.enabled=false, or too short to come back?)");
  if (run.measurements.empty())
    throw std::runtime_error(records_path + ": " + std::to_string(run.tried) +
                             " loop closures were tried and none refined a posture to measure");
  return run;
}

nlohmann::json StatisticsJson(const ErrorStatistics& s) {
  return {{"mean", s.mean}, {"std", s.std}, {"max", s.max}};
}

nlohmann::json TallyJson(const ClosureTally& tally) {
  return {{"closures", tally.closures},
          {"with_reference", tally.evaluation.matched},
          {"right", tally.right},
          {"translation_m", StatisticsJson(tally.evaluation.translation_m)},
          {"rotation_deg", StatisticsJson(tally.evaluation.rotation_deg)}};
}

nlohmann::json ClosuresJson(const RunClosures& run, const ClosurePrecision& precision) {
  nlohmann::json closures = nlohmann::json::array();
  for (std::size_t i = 0; i < run.rows.size(); ++i) {
    const IterationRow& row = *run.rows[i];
    nlohmann::json closure = {{"iteration", row.index},
                              {"old_iteration", row.closure->old_iteration},
                              {"node", row.closure->node},
                              {"old_node", row.closure->old_node},
                              {"reason", row.closure->reason},
                              {"accepted", run.measurements[i].accepted},
                              {"in_graph", run.measurements[i].in_graph},
                              {"error", nullptr},
                              {"right", nullptr}};
    if (const std::optional<Pose2D>& e = precision.errors[i]) {
      closure["error"] = {
          {"x_m", e->x_m},
          {"y_m", e->y_m},
          {"yaw_rad", e->yaw_rad},
          {"translation_m", e->Translation().norm()},
          {"rotation_deg", std::abs(NormalizeAngle(e->yaw_rad)) * kDegreesPerRadian}};
      closure["right"] = static_cast<bool>(precision.right[i]);
    }
    closures.push_back(closure);
  }
  return closures;
}

void PrintTally(const char* name, const ClosureTally& tally) {
  const std::size_t with_reference = tally.evaluation.matched;
  std::printf("  %-13s %4zu of %4zu", name, tally.right, with_reference);
  if (with_reference > 0)
    std::printf(" (%3.0f %%)   error %.3f ± %.3f m (max %.3f), %.2f ± %.2f° (max %.2f)",
                100.0 * static_cast<double>(tally.right) / static_cast<double>(with_reference),
                tally.evaluation.translation_m.mean, tally.evaluation.translation_m.std,
                tally.evaluation.translation_m.max, tally.evaluation.rotation_deg.mean,
                tally.evaluation.rotation_deg.std, tally.evaluation.rotation_deg.max);
  if (with_reference < tally.closures)
    std::printf("   [%zu without reference poses]", tally.closures - with_reference);
  std::printf("\n");
}

// The bins of how far a closure moved its scan from the session's posture, metres.
const std::vector<double> kDisagreementEdgesM = {0.02, 0.04, 0.08, 0.16};

// The session's own postures of the closures' scans: the online trajectory (what the session gave
// before any graph correction), or nothing when the run has none.
std::optional<std::pair<std::string, std::vector<StampedPose>>> SessionPostures(
    const std::filesystem::path& folder) {
  const std::filesystem::path path = folder / "trajectory-online.tum";
  if (!std::filesystem::exists(path)) return std::nullopt;
  return std::make_pair(path.filename().string(), ReadTumTrajectory(path.string()));
}

void PrintBeside(const std::string& trajectory_name, const ClosuresBesideTrajectory& beside,
                 bool graph_known) {
  std::printf("the session's own postures of the same scans (%s), %zu closures",
              trajectory_name.c_str(), beside.compared.size());
  if (beside.not_in_trajectory > 0)
    std::printf(" (%zu more have a scan it lacks)", beside.not_in_trajectory);
  std::printf(":\n");
  PrintTally("measured", beside.trajectory.measured);
  PrintTally("accepted", beside.trajectory.accepted);
  if (graph_known) PrintTally("in the graph", beside.trajectory.in_graph);
  std::printf("right, by how far the closure moved the scan from the session's posture:\n");
  for (const DisagreementBin& bin : RightByDisagreement(beside, kDisagreementEdgesM)) {
    if (std::isinf(bin.to_m))
      std::printf("  >= %.2f m      ", bin.from_m);
    else
      std::printf("  %.2f–%.2f m    ", bin.from_m, bin.to_m);
    std::printf("%4zu closures   closure right %4zu   session right %4zu\n", bin.closures,
                bin.closure_right, bin.trajectory_right);
  }
}

nlohmann::json BesideJson(const std::string& trajectory_name,
                          const ClosuresBesideTrajectory& beside, bool graph_known) {
  nlohmann::json bins = nlohmann::json::array();
  for (const DisagreementBin& bin : RightByDisagreement(beside, kDisagreementEdgesM))
    bins.push_back(
        {{"from_m", bin.from_m},
         {"to_m", std::isinf(bin.to_m) ? nlohmann::json(nullptr) : nlohmann::json(bin.to_m)},
         {"closures", bin.closures},
         {"closure_right", bin.closure_right},
         {"session_right", bin.trajectory_right}});
  return {{"trajectory", trajectory_name},
          {"compared", beside.compared.size()},
          {"not_in_trajectory", beside.not_in_trajectory},
          {"measured", TallyJson(beside.trajectory.measured)},
          {"accepted", TallyJson(beside.trajectory.accepted)},
          {"in_graph", graph_known ? TallyJson(beside.trajectory.in_graph) : nullptr},
          {"by_disagreement", bins}};
}

// Each compared closure's record gains how far it moved its scan from the session's posture and
// whether the session's own posture was right.
void AddSessionPerClosure(const ClosuresBesideTrajectory& beside, nlohmann::json& closures) {
  for (std::size_t k = 0; k < beside.compared.size(); ++k) {
    nlohmann::json& closure = closures[beside.compared[k]];
    closure["moved_from_session_m"] = beside.disagreement_m[k];
    closure["session_right"] = nullptr;
    if (beside.trajectory.errors[k]) closure["session_right"] = bool(beside.trajectory.right[k]);
  }
}

void PrintText(const ClosureEvaluationArguments& a, const RunClosures& run,
               const ClosurePrecision& precision, const EvaluationFrame& frame) {
  std::printf("closures: %zu tried, %zu measured, %zu accepted", run.tried,
              precision.measured.closures, precision.accepted.closures);
  if (run.graph_known) std::printf(", %zu in the graph", precision.in_graph.closures);
  std::printf("\nreference poses taken as the scans': %s\n", Describe(frame).c_str());
  std::printf("right (within %.3g m and %.3g° of the reference), of those with reference poses:\n",
              a.max_error_m, a.max_error_deg);
  PrintTally("measured", precision.measured);
  PrintTally("accepted", precision.accepted);
  if (run.graph_known) PrintTally("in the graph", precision.in_graph);
}

}  // namespace

void EvaluateRunClosures(const ClosureEvaluationArguments& a) {
  const std::filesystem::path folder(a.run_folder);
  const IterationRows records = ReadIterationRows((folder / "iterations.jsonl").string());
  if (records.truncated_last_line)
    std::cerr << "warning: " << (folder / "iterations.jsonl").string()
              << ": the last record was cut short and is left out\n";
  const RunClosures run = ReadRunClosures(folder, records);
  if (!run.graph_known)
    std::cerr << "warning: " << a.run_folder
              << " has no graph.g2o: the closures kept in the graph are not counted\n";
  ClosurePrecisionOptions options;
  options.timestamp_tolerance_s = a.tolerance_s;
  options.max_translation_error_m = a.max_error_m;
  options.max_rotation_error_deg = a.max_error_deg;
  const EvaluationFrame frame = ResolveEvaluationFrame(a.mounting, a.run_folder);
  std::vector<StampedPose> reference = ReadReferencePoses(a.reference_path);
  for (StampedPose& pose : reference) pose.pose = frame.mounting.RobotPose(pose.pose);
  const ClosurePrecision precision = EvaluateClosures(run.measurements, reference, options);
  if (precision.measured.evaluation.matched == 0)
    throw std::runtime_error("no measured closure has reference poses for both of its scans (" +
                             std::to_string(run.measurements.size()) +
                             " closures; timestamp tolerance " + std::to_string(a.tolerance_s) +
                             " s): are " + a.reference_path + " and " + a.run_folder +
                             " of the same log?");
  const auto session = SessionPostures(folder);
  std::optional<ClosuresBesideTrajectory> beside;
  if (session)
    beside = CompareWithTrajectory(run.measurements, reference, session->second, options);
  else
    std::cerr << "warning: " << a.run_folder
              << " has no trajectory-online.tum: the closures are not compared with the "
                 "session's own postures\n";
  if (!a.json) {
    PrintText(a, run, precision, frame);
    if (beside) PrintBeside(session->first, *beside, run.graph_known);
    return;
  }
  nlohmann::json out = {{"tried", run.tried},
                        {"measured", TallyJson(precision.measured)},
                        {"accepted", TallyJson(precision.accepted)},
                        {"in_graph", nullptr},
                        {"closures", ClosuresJson(run, precision)}};
  if (run.graph_known) out["in_graph"] = TallyJson(precision.in_graph);
  out["laser_mounting"] = ToJson(frame);
  out["session"] = beside ? BesideJson(session->first, *beside, run.graph_known) : nullptr;
  if (beside) AddSessionPerClosure(*beside, out["closures"]);
  std::cout << out.dump(2) << '\n';
}

}  // namespace scanloc::app
