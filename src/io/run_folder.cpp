#include "scanloc/io/run_folder.hpp"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "scanloc/common/atomic_file.hpp"
#include "scanloc/common/output_folder.hpp"
#include "scanloc/io/candidate_report.hpp"
#include "scanloc/io/g2o_file.hpp"
#include "scanloc/io/occupancy_grid_io.hpp"
#include "scanloc/io/record_keys.hpp"
#include "scanloc/maps/point_map_io.hpp"

namespace scanloc {
namespace keys = record_keys;

namespace {

// The refinements of one localisation, each re-validated, as the report lists them.
nlohmann::json RefinedCandidatesJson(const LocalisationResult& localisation) {
  nlohmann::json refined = nlohmann::json::array();
  for (const RankedCandidate& candidate : localisation.refined)
    refined.push_back({{keys::kCandidate, candidate.candidate.label},
                       {keys::kTWorldLaser, ToJson(candidate.T_world_laser)},
                       {keys::kCost, candidate.cost},
                       {keys::kRank, candidate.rank},
                       {keys::kValid, candidate.verdict == Verdict::kValid},
                       {keys::kReason, ToString(candidate.verdict)},
                       {keys::kExpectValueM, candidate.test.expect_value_m},
                       {keys::kMatchRatio, candidate.test.MatchRatio()}});
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
                        {keys::kHalfWidthM, c.window.half_width_m},
                        {keys::kHalfYawRad, c.window.half_yaw_rad},
                        {keys::kMatched, ToJson(c.T_world_robot_matched)},
                        {keys::kTOldRobot, ToJson(c.T_old_robot)},
                        {keys::kLargestShiftM, c.largest_shift_m},
                        {keys::kRendered, c.rendered},
                        {keys::kTimeS, c.time_s}};
  if (c.test) {
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
                   {keys::kValidated, h.validated}});
  return out;
}

}  // namespace

nlohmann::json ToJson(const IterationRecord& r) {
  const LocalisationResult* localisation = r.localisation ? &*r.localisation : nullptr;
  const double evaluate_s = localisation ? localisation->evaluate_s : 0.0;
  const double refine_s = localisation ? localisation->refine_s : 0.0;
  nlohmann::json out = {{keys::kIndex, r.index},
                        {keys::kTimestampS, r.timestamp_s},
                        {keys::kOrigin, r.origin},
                        {keys::kSkipped, r.skipped},
                        {keys::kFirst, r.first},
                        {keys::kPrediction, ToJson(r.prediction)},
                        {keys::kTWorldRobot, ToJson(r.T_world_robot)},
                        {keys::kValidated, r.validated},
                        {keys::kReason, ToString(r.verdict)},
                        {keys::kInserted, r.inserted},
                        {keys::kCarved, r.carved},
                        {keys::kMapPoints, r.map_points},
                        {keys::kTimingsMs,
                         {{keys::kEvaluate, 1e3 * evaluate_s},
                          {keys::kRefine, 1e3 * refine_s},
                          {keys::kInsert, 1e3 * r.insert_s},
                          {keys::kTotal, 1e3 * r.total_s}}}};
  if (r.lost) out[keys::kLost] = true;
  if (r.recovered) out[keys::kRecovered] = true;
  if (!r.state.empty()) {
    out[keys::kState] = r.state;
    out[keys::kPosed] = r.posed;
    out[keys::kHypotheses] = HypothesesJson(r.hypotheses);
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
    out["candidates"] = EvaluatedToJson(*localisation)["candidates"];
    out["chosen"] = kept ? nlohmann::json(kept->candidate.label) : nlohmann::json(nullptr);
    out["problems"] = localisation->problems;
    out[keys::kMaxExpectValueM] = r.max_expect_value_m;
    out[keys::kSignatureExpectValueM] = r.signature_expect_value_m;
  }
  if (kept) {
    out["refinement"] = ToJson(*kept->refinement);
    out["refined_candidates"] = RefinedCandidatesJson(*localisation);
    const Pose2D correction = Between(r.prediction, r.T_world_robot);
    out["correction_from_prediction_mm_mm_mrad"] = {1e3 * correction.x_m, 1e3 * correction.y_m,
                                                    1e3 * correction.yaw_rad};
  }
  return out;
}

RunFolder::RunFolder(const std::string& directory, bool overwrite) : directory_(directory) {
  RefuseNonEmptyFolder(directory_, overwrite);
  std::error_code error;
  std::filesystem::create_directories(directory_, error);
  if (error || !std::filesystem::is_directory(directory_))
    throw std::runtime_error("cannot create the run folder " + directory_ + ": " + error.message());
  records_.open(Path("iterations.jsonl"), std::ios::trunc);
  if (!records_) throw std::runtime_error("cannot write " + Path("iterations.jsonl"));
}

void RunFolder::Record(const IterationRecord& record) {
  records_ << ToJson(record).dump() << '\n';
  records_.flush();  // a line is complete on disk before the next iteration starts
  if (!records_) throw std::runtime_error("error while writing " + Path("iterations.jsonl"));
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
  summary["files"] = {{keys::kIterations, "iterations.jsonl"},
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
