#include "scanloc/io/run_folder.hpp"

#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <utility>

#include "scanloc/common/atomic_file.hpp"
#include "scanloc/common/output_folder.hpp"
#include "scanloc/common/parse_error.hpp"
#include "scanloc/io/candidate_report.hpp"
#include "scanloc/io/g2o_file.hpp"
#include "scanloc/io/json_text.hpp"
#include "scanloc/io/occupancy_grid_io.hpp"
#include "scanloc/io/record_keys.hpp"
#include "scanloc/maps/point_map_io.hpp"

namespace scanloc {
namespace keys = record_keys;

namespace {

// The refinements of one localisation, each re-validated, as the report lists them.
nlohmann::json RefinedCandidatesJson(const LocalisationResult& localisation) {
  nlohmann::json refined = nlohmann::json::array();
  for (const RankedCandidate& candidate : localisation.refined) {
    // Member by member, as the candidate reports (see candidate_report.cpp).
    nlohmann::json& out = refined.emplace_back(nlohmann::json::object());
    out[keys::kCandidate] = candidate.candidate.label;
    out[keys::kTWorldLaser] = ToJson(candidate.T_world_laser);
    out[keys::kCost] = candidate.cost;
    out[keys::kRank] = candidate.rank;
    out[keys::kValid] = candidate.verdict == Verdict::kValid;
    out[keys::kReason] = ToString(candidate.verdict);
    out[keys::kExpectValueM] = candidate.test.expect_value_m;
    out[keys::kMatchRatio] = candidate.test.MatchRatio();
  }
  return refined;
}

// A loop closure tried: where, against how many old nodes, the rules' verdict and the correction.
nlohmann::json ClosureJson(const ClosureAttempt& c) {
  nlohmann::json out = {{keys::kAccepted, c.accepted},
                        {keys::kReason, c.reason},
                        {keys::kNode, c.node},
                        {keys::kOldNode, c.old_node},
                        {keys::kOldIteration, c.old_iteration},
                        {keys::kLocalNodes, c.local_nodes},
                        {keys::kPathSinceM, c.path_since_m},
                        {keys::kChainSigmaM, c.chain_sigma_m},
                        {keys::kChainSigmaRad, c.chain_sigma_rad},
                        {keys::kHalfWidthM, c.window.half_width_m},
                        {keys::kHalfYawRad, c.window.half_yaw_rad},
                        {keys::kPredictedShiftM, c.predicted_shift_m},
                        {keys::kSolveDeferred, c.solve_deferred},
                        {keys::kLargestShiftM, c.largest_shift_m},
                        {keys::kSolveIterations, c.solve_iterations},
                        {keys::kRendered, c.rendered},
                        {keys::kTimeS, c.time_s}};
  if (c.test) {  // something was refined: the posture matched and the closure's measurement
    out[keys::kMatched] = ToJson(c.T_world_robot_matched);
    out[keys::kTOldRobot] = ToJson(c.T_old_robot);
    out[keys::kExpectValueM] = c.test->expect_value_m;
    out[keys::kMatchRatio] = c.test->MatchRatio();
  }
  return out;
}

// The hypotheses a localisation holds, best first.
nlohmann::json HypothesesJson(const std::vector<Hypothesis>& hypotheses) {
  nlohmann::json out = nlohmann::json::array();
  for (const Hypothesis& h : hypotheses)
    out.push_back({{keys::kTWorldRobot, ToJson(h.T_world_robot)},
                   {keys::kConfirmedInRow, h.confirmed_in_row},
                   {keys::kUnconfirmedInRow, h.unconfirmed_in_row},
                   {keys::kConfirmations, h.confirmations},
                   {keys::kSearches, h.searches},
                   {keys::kHeld, h.held},
                   {keys::kCost, h.cost},
                   {keys::kValidated, h.validated},
                   {keys::kReason, ToString(h.verdict)},
                   {keys::kExpectValueM, h.expect_value_m},
                   {keys::kMatchRatio, h.match_ratio},
                   {keys::kTruncatedMeanM, h.truncated_mean_m}});
  return out;
}

// The files a session writes into its run folder, and those it writes at the end.
const std::vector<std::string> kFinalFiles = {
    "summary.json", "trajectory.tum", "trajectory-online.tum", "map.pcd", "map.pgm",
    "map.yaml",     "graph.g2o"};
const std::vector<std::string> kRunFiles = [] {
  std::vector<std::string> files = kFinalFiles;
  files.push_back("run.json");
  files.push_back("iterations.jsonl");
  return files;
}();

void RemoveFiles(const std::string& directory, const std::vector<std::string>& names) {
  for (const std::string& name : names) {
    std::error_code error;
    std::filesystem::remove(directory + "/" + name, error);
    if (error)
      throw std::runtime_error("cannot remove " + directory + "/" + name + ": " + error.message());
  }
}

// The JSON paths where `b` differs from `a`, e.g. "/config/loop_closure/enabled" (the first five).
std::string DifferingPaths(const nlohmann::json& a, const nlohmann::json& b) {
  const nlohmann::json patch = nlohmann::json::diff(a, b);
  std::string paths;
  for (std::size_t i = 0; i < patch.size() && i < 5; ++i)
    paths += (i > 0 ? ", " : "") + patch[i]["path"].get<std::string>();
  if (patch.size() > 5) paths += " and " + std::to_string(patch.size() - 5) + " more";
  return paths;
}

}  // namespace

nlohmann::json ToJson(const IterationRecord& r) {
  const LocalisationResult* localisation = r.localisation ? &*r.localisation : nullptr;
  const double evaluate_s = localisation ? localisation->evaluate_s : 0.0;
  const double refine_s = localisation ? localisation->refine_s : 0.0;
  nlohmann::json out = nlohmann::json::object();  // member by member (see candidate_report.cpp)
  out[keys::kIndex] = r.index;
  out[keys::kTimestampS] = r.timestamp_s;
  out[keys::kOrigin] = r.origin;
  out[keys::kSkipped] = r.skipped;
  out[keys::kFirst] = r.first;
  out[keys::kPrediction] = ToJson(r.prediction);
  out[keys::kTWorldRobot] = ToJson(r.T_world_robot);
  out[keys::kValidated] = r.validated;
  out[keys::kReason] = ToString(r.verdict);
  out[keys::kInserted] = r.inserted;
  out[keys::kCarved] = r.carved;
  out[keys::kMapPoints] = r.map_points;
  nlohmann::json& timings = out[keys::kTimingsMs];
  timings[keys::kEvaluate] = 1e3 * evaluate_s;
  timings[keys::kRefine] = 1e3 * refine_s;
  timings[keys::kInsert] = 1e3 * r.insert_s;
  timings[keys::kTotal] = 1e3 * r.total_s;
  if (r.lost) out[keys::kLost] = true;
  if (r.recovered) out[keys::kRecovered] = true;
  if (!r.state.empty()) {
    out[keys::kState] = r.state;
    out[keys::kPosed] = r.posed;
    out[keys::kHypotheses] = HypothesesJson(r.hypotheses);
    if (!r.discarded.empty()) out[keys::kDiscarded] = r.discarded;
  }
  if (r.closure) out[keys::kClosure] = ClosureJson(*r.closure);
  if (r.search_window && r.search) {
    const SearchWindow& w = *r.search_window;
    out[keys::kSearch] = {{keys::kCentre, ToJson(w.centre)},
                          {keys::kHalfWidthM, w.half_width_m},
                          {keys::kHalfYawRad, w.half_yaw_rad},
                          {keys::kHeadings, r.search->headings},
                          {keys::kNodesScored, r.search->nodes_scored},
                          {keys::kFound, r.search->candidates.size()},
                          {keys::kTimeS, r.search->time_s}};
  }
  const RankedCandidate* kept = r.Kept();
  if (localisation && !localisation->evaluated.empty()) {
    // Moved, not copied: the candidates are the bulk of a record.
    nlohmann::json evaluated = EvaluatedToJson(*localisation);
    out["candidates"] = std::move(evaluated["candidates"]);
    out["chosen"] = kept ? nlohmann::json(kept->candidate.label) : nlohmann::json(nullptr);
    out["problems"] = localisation->problems;
    out[keys::kMaxExpectValueM] = r.max_expect_value_m;
    out[keys::kSignatureExpectValueM] = r.signature_expect_value_m;
    if (r.correction_bound)
      out[keys::kCorrectionBound] = {r.correction_bound->translation_m,
                                     r.correction_bound->rotation_rad};
  }
  if (kept) {
    // The posture the correction gate refused: the kept refinement, the scan took the prediction.
    if (r.beyond_odometry) out[keys::kBeyondOdometry] = ToJson(kept->T_world_robot);
    out["refinement"] = ToJson(*kept->refinement);
    out["refined_candidates"] = RefinedCandidatesJson(*localisation);
    const Pose2D correction = Between(r.prediction, r.T_world_robot);
    out["correction_from_prediction_mm_mm_mrad"] = {1e3 * correction.x_m, 1e3 * correction.y_m,
                                                    1e3 * correction.yaw_rad};
  }
  return out;
}

RunFolder::RunFolder(const std::string& directory, bool overwrite)
    : RunFolder(directory, overwrite ? RunFolderOpening::kOverwrite : RunFolderOpening::kNew) {}

RunFolder::RunFolder(const std::string& directory, RunFolderOpening opening)
    : directory_(directory) {
  if (opening == RunFolderOpening::kResume) {
    Resume();
    return;
  }
  RefuseNonEmptyFolder(directory_, opening == RunFolderOpening::kOverwrite);
  std::error_code error;
  std::filesystem::create_directories(directory_, error);
  if (error || !std::filesystem::is_directory(directory_))
    throw std::runtime_error("cannot create the run folder " + directory_ + ": " + error.message());
  // An earlier run's files go first, its summary before the rest: no new record ever sits beside
  // an old summary or map.
  if (opening == RunFolderOpening::kOverwrite) RemoveFiles(directory_, kRunFiles);
  records_.open(Path("iterations.jsonl"), std::ios::trunc);
  if (!records_) throw std::runtime_error("cannot write " + Path("iterations.jsonl"));
}

void RunFolder::Resume() {
  resuming_ = true;
  const std::string records = Path("iterations.jsonl");
  if (!std::filesystem::is_regular_file(records))
    throw std::runtime_error(directory_ + " holds no iterations.jsonl: there is no run to resume");
  RecordedRun run = ReadRecordsToResume(records);
  recorded_ = std::move(run.iterations);
  std::error_code error;
  if (run.partial_line) std::filesystem::resize_file(records, run.complete_bytes, error);
  records_.open(records, std::ios::app);
  if (error || !records_)
    throw std::runtime_error("cannot write " + records + (error ? ": " + error.message() : ""));
}

void RunFolder::Begin(const nlohmann::json& identity) {
  const std::string path = Path("run.json");
  if (!resuming_) {
    WriteFileAtomically(path, [&](std::ostream& out) { out << identity.dump(2) << '\n'; });
    return;
  }
  std::ifstream in(path);
  if (!in)
    throw std::runtime_error(path + " is missing: only a run folder written by `scanloc session` " +
                             "can be resumed");
  nlohmann::json stored;
  try {
    stored = nlohmann::json::parse(in);
  } catch (const nlohmann::json::exception& e) {
    throw ParseError(
        path, 1, std::string("expected the JSON of what the run was started with: ") + e.what());
  }
  if (stored != identity)
    throw std::runtime_error(
        "--resume needs the inputs and options the run was started with; these differ from " +
        path + ": " + DifferingPaths(stored, identity));
}

void RunFolder::Record(const IterationRecord& record) {
  if (resuming_ && !appended_) {
    // The first new record: the interrupted run's outputs no longer describe the folder.
    RemoveFiles(directory_, kFinalFiles);
  }
  appended_ = true;
  std::string line;
  AppendJsonText(ToJson(record), line);
  line += '\n';
  records_ << line;
  records_.flush();  // a line is complete on disk before the next iteration starts
  if (!records_)     // the failed write(2)'s errno, e.g. "No space left on device"
    throw std::runtime_error("cannot write " + Path("iterations.jsonl") + ": " +
                             std::strerror(errno));
  Replayed(record);
}

void RunFolder::Replayed(const IterationRecord& record) {
  if (!record.posed) return;
  trajectory_.push_back({record.timestamp_s, record.T_world_robot});
  trajectory_records_.push_back(record.index);
}

void RunFolder::Correct(const std::vector<std::optional<Pose2D>>& postures) {
  if (postures.empty()) return;
  online_trajectory_ = trajectory_;
  for (std::size_t i = 0; i < trajectory_.size(); ++i) {
    const std::size_t record = trajectory_records_[i];
    if (record < postures.size() && postures[record]) trajectory_[i].pose = *postures[record];
  }
}

void RunFolder::WriteGraph(const PoseGraph& graph) {
  WriteG2o(graph, Path("graph.g2o"));
  wrote_graph_ = true;
}

void RunFolder::Finish(const PointMap& map, nlohmann::json summary, const OccupancyGrid* grid) {
  records_.close();
  WriteTumTrajectory(Path("trajectory.tum"), trajectory_);
  SavePointMapPcd(map, Path("map.pcd"));
  summary["files"] = {{"run", "run.json"},
                      {keys::kIterations, "iterations.jsonl"},
                      {"trajectory", "trajectory.tum"},
                      {"map", "map.pcd"}};
  if (!online_trajectory_.empty()) {
    WriteTumTrajectory(Path("trajectory-online.tum"), online_trajectory_);
    summary["files"]["trajectory_online"] = "trajectory-online.tum";
  }
  if (wrote_graph_) summary["files"]["pose_graph"] = "graph.g2o";
  if (grid) {
    WriteOccupancyGrid(directory_, *grid);
    summary["files"]["occupancy_grid"] = "map.yaml";
  }
  WriteFileAtomically(Path("summary.json"),
                      [&](std::ostream& out) { out << summary.dump(2) << '\n'; });
}

}  // namespace scanloc
