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
#include "scanloc/io/json_writer.hpp"
#include "scanloc/io/occupancy_grid_io.hpp"
#include "scanloc/io/record_keys.hpp"
#include "scanloc/maps/point_map_io.hpp"

namespace scanloc {
namespace keys = record_keys;

namespace {

// The refinements of one localisation, each re-validated, as the report lists them.
void WriteRefinedCandidates(JsonWriter& out, const LocalisationResult& localisation) {
  out.BeginArray();
  for (const RankedCandidate& candidate : localisation.refined) {
    out.BeginObject();
    out.Member(keys::kCandidate, candidate.candidate.label);
    out.Key(keys::kTWorldLaser);
    WriteJson(out, candidate.T_world_laser);
    out.Member(keys::kCost, candidate.cost);
    out.Member(keys::kRank, candidate.rank);
    out.Member(keys::kValid, candidate.verdict == Verdict::kValid);
    out.Member(keys::kReason, ToString(candidate.verdict));
    out.Member(keys::kExpectValueM, candidate.test.expect_value_m);
    out.Member(keys::kMatchRatio, candidate.test.MatchRatio());
    out.EndObject();
  }
  out.EndArray();
}

// A loop closure tried: where, against how many old nodes, the rules' verdict and the correction.
void WriteClosure(JsonWriter& out, const ClosureAttempt& c) {
  out.BeginObject();
  out.Member(keys::kAccepted, c.accepted);
  out.Member(keys::kReason, c.reason);
  out.Member(keys::kNode, c.node);
  out.Member(keys::kOldNode, c.old_node);
  out.Member(keys::kOldIteration, c.old_iteration);
  out.Member(keys::kLocalNodes, c.local_nodes);
  out.Member(keys::kPathSinceM, c.path_since_m);
  out.Member(keys::kChainSigmaM, c.chain_sigma_m);
  out.Member(keys::kChainSigmaRad, c.chain_sigma_rad);
  out.Member(keys::kHalfWidthM, c.window.half_width_m);
  out.Member(keys::kHalfYawRad, c.window.half_yaw_rad);
  out.Member(keys::kFromRun, c.from_run);
  out.Member(keys::kPredictedShiftM, c.predicted_shift_m);
  out.Member(keys::kSolveDeferred, c.solve_deferred);
  out.Member(keys::kLargestShiftM, c.largest_shift_m);
  out.Member(keys::kSolveIterations, c.solve_iterations);
  out.Member(keys::kRendered, c.rendered);
  out.Member(keys::kTimeS, c.time_s);
  if (c.test) {  // something was refined: the posture matched and the closure's measurement
    out.Key(keys::kMatched);
    WriteJson(out, c.T_world_robot_matched);
    out.Key(keys::kTOldRobot);
    WriteJson(out, c.T_old_robot);
    out.Member(keys::kExpectValueM, c.test->expect_value_m);
    out.Member(keys::kMatchRatio, c.test->MatchRatio());
  }
  out.EndObject();
}

// The hypotheses a localisation holds, best first.
void WriteHypotheses(JsonWriter& out, const std::vector<Hypothesis>& hypotheses) {
  out.BeginArray();
  for (const Hypothesis& h : hypotheses) {
    out.BeginObject();
    out.Key(keys::kTWorldRobot);
    WriteJson(out, h.T_world_robot);
    out.Member(keys::kConfirmedInRow, h.confirmed_in_row);
    out.Member(keys::kUnconfirmedInRow, h.unconfirmed_in_row);
    out.Member(keys::kConfirmations, h.confirmations);
    out.Member(keys::kSearches, h.searches);
    out.Member(keys::kHeld, h.held);
    out.Member(keys::kCost, h.cost);
    out.Member(keys::kValidated, h.validated);
    out.Member(keys::kReason, ToString(h.verdict));
    out.Member(keys::kExpectValueM, h.expect_value_m);
    out.Member(keys::kMatchRatio, h.match_ratio);
    out.Member(keys::kTruncatedMeanM, h.truncated_mean_m);
    out.EndObject();
  }
  out.EndArray();
}

// The wide search a lost session made before localising the scan: its window and what it found.
void WriteSearch(JsonWriter& out, const SearchWindow& w, const WideSearchResult& search) {
  out.BeginObject();
  out.Key(keys::kCentre);
  WriteJson(out, w.centre);
  out.Member(keys::kHalfWidthM, w.half_width_m);
  out.Member(keys::kHalfYawRad, w.half_yaw_rad);
  out.Member(keys::kHeadings, search.headings);
  out.Member(keys::kNodesScored, search.nodes_scored);
  out.Member(keys::kFound, search.candidates.size());
  out.Member(keys::kTimeS, search.time_s);
  out.EndObject();
}

// Where the scan came from, the posture kept and what the rules said of it, what it did to the
// map and the time it took.
void WriteOutcome(JsonWriter& out, const IterationRecord& r) {
  const LocalisationResult* localisation = r.localisation ? &*r.localisation : nullptr;
  out.Member(keys::kIndex, r.index);
  out.Member(keys::kTimestampS, r.timestamp_s);
  out.Member(keys::kOrigin, r.origin);
  out.Member(keys::kSkipped, r.skipped);
  out.Member(keys::kFirst, r.first);
  out.Key(keys::kPrediction);
  WriteJson(out, r.prediction);
  out.Key(keys::kTWorldRobot);
  WriteJson(out, r.T_world_robot);
  out.Member(keys::kValidated, r.validated);
  out.Member(keys::kReason, ToString(r.verdict));
  out.Member(keys::kInserted, r.inserted);
  // Extended the map at the prediction, on new ground (new_ground.hpp).
  if (r.new_ground) out.Member(keys::kNewGround, true);
  out.Member(keys::kCarved, r.carved);
  out.Member(keys::kMapPoints, r.map_points);
  out.Key(keys::kTimingsMs);
  out.BeginObject();
  out.Member(keys::kEvaluate, 1e3 * (localisation ? localisation->evaluate_s : 0.0));
  out.Member(keys::kRefine, 1e3 * (localisation ? localisation->refine_s : 0.0));
  out.Member(keys::kInsert, 1e3 * r.insert_s);
  out.Member(keys::kTotal, 1e3 * r.total_s);
  out.EndObject();
  if (r.lost) out.Member(keys::kLost, true);
  if (r.recovered) out.Member(keys::kRecovered, true);
  if (r.motion_search) out.Member(keys::kMotionSearch, true);
  if (r.without_odometry) out.Member(keys::kWithoutOdometry, true);
  if (r.odometry_frozen) out.Member(keys::kOdometryFrozen, true);
  if (r.odometry_from_scans) out.Member(keys::kOdometryFromScans, true);
  if (r.motion_searched_hypotheses > 0)
    out.Member(keys::kMotionSearchedHypotheses, r.motion_searched_hypotheses);
  if (r.not_evidence) out.Member(keys::kEvidence, false);
}

// The candidates tried and the refinement kept, when the scan was localised.
void WriteLocalisation(JsonWriter& out, const IterationRecord& r) {
  const LocalisationResult* localisation = r.localisation ? &*r.localisation : nullptr;
  const RankedCandidate* kept = r.Kept();
  if (localisation && !localisation->evaluated.empty()) {
    out.Key(keys::kCandidates);
    WriteEvaluatedCandidates(out, *localisation);
    out.Key(keys::kChosen);
    if (kept)
      out.Value(kept->candidate.label);
    else
      out.Null();
    out.Member(keys::kProblems, localisation->problems);
    out.Member(keys::kMaxExpectValueM, r.max_expect_value_m);
    out.Member(keys::kSignatureExpectValueM, r.signature_expect_value_m);
    if (r.correction_bound)
      out.Member(keys::kCorrectionBound, std::vector<double>{r.correction_bound->translation_m,
                                                             r.correction_bound->rotation_rad});
    // The slide check (correction_drift.hpp): the summed corrections before and with this one,
    // and the bound in force.
    if (r.slide_check)
      out.Member(keys::kCorrectionSum,
                 std::vector<double>{r.slide_check->before_m, r.slide_check->after_m,
                                     r.slide_check->bound_m});
  }
  if (!kept) return;
  // The posture the correction gate refused: the kept refinement, the scan took the prediction.
  if (r.beyond_odometry) {
    out.Key(keys::kBeyondOdometry);
    WriteJson(out, kept->T_world_robot);
  }
  // The posture refused as adding up to a slide (correction_drift.hpp).
  if (r.slide_refused) {
    out.Key(keys::kSlideRefused);
    WriteJson(out, kept->T_world_robot);
  }
  // The posture a closure's dispute withdrew (turn_dispute.hpp): the scan took the prediction.
  if (r.turn_dispute) {
    out.Key(keys::kTurnDisputed);
    out.BeginObject();
    out.Key(keys::kTracked);
    WriteJson(out, r.turn_dispute->T_world_robot_tracked);
    out.Member(keys::kCorrectionRad, r.turn_dispute->correction_rad);
    out.Member(keys::kClosureFromPredictionRad, r.turn_dispute->closure_from_prediction_rad);
    out.Member(keys::kClosureFromTrackedRad, r.turn_dispute->closure_from_tracked_rad);
    out.EndObject();
  }
  out.Key(keys::kRefinement);
  WriteJson(out, *kept->refinement);
  out.Key(keys::kRefinedCandidates);
  WriteRefinedCandidates(out, *localisation);
  // The refinement the rules ranked first, where the session kept a tighter one
  // (tighter_refinement.hpp): its index in the refined candidates.
  if (r.outranked_refinement >= 0) out.Member(keys::kOutrankedRefinement, r.outranked_refinement);
  const Pose2D correction = Between(r.prediction, r.T_world_robot);
  out.Member(
      keys::kCorrectionFromPredictionMmMmMrad,
      std::vector<double>{1e3 * correction.x_m, 1e3 * correction.y_m, 1e3 * correction.yaw_rad});
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

void WriteRecord(const IterationRecord& r, std::string& text) {
  JsonWriter out(text);
  out.BeginObject();
  WriteOutcome(out, r);
  if (!r.state.empty()) {
    out.Member(keys::kState, r.state);
    out.Member(keys::kPosed, r.posed);
    out.Key(keys::kHypotheses);
    WriteHypotheses(out, r.hypotheses);
    if (!r.discarded.empty()) out.Member(keys::kDiscarded, r.discarded);
  }
  if (r.closure) {
    out.Key(keys::kClosure);
    WriteClosure(out, *r.closure);
  }
  if (r.search_window && r.search) {
    out.Key(keys::kSearch);
    WriteSearch(out, *r.search_window, *r.search);
  }
  WriteLocalisation(out, r);
  out.EndObject();
}

nlohmann::json ToJson(const IterationRecord& record) {
  std::string text;
  WriteRecord(record, text);
  return nlohmann::json::parse(text);
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
  line_.clear();
  WriteRecord(record, line_);
  line_ += '\n';
  records_ << line_;
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
