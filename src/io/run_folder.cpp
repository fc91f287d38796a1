#include "scanloc/io/run_folder.hpp"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>

#include "scanloc/common/atomic_file.hpp"
#include "scanloc/io/candidate_report.hpp"
#include "scanloc/maps/point_map_io.hpp"

namespace scanloc {

namespace {

// The refinements of one localisation, each re-validated, as the report lists them.
nlohmann::json RefinedCandidatesJson(const LocalisationResult& localisation) {
  nlohmann::json refined = nlohmann::json::array();
  for (const RankedCandidate& candidate : localisation.refined)
    refined.push_back({{"candidate", candidate.candidate.label},
                       {"T_world_laser", ToJson(candidate.T_world_laser)},
                       {"cost", candidate.cost},
                       {"rank", candidate.rank},
                       {"valid", candidate.verdict == Verdict::kValid},
                       {"reason", ToString(candidate.verdict)},
                       {"expect_value_m", candidate.test.expect_value_m},
                       {"match_ratio", candidate.test.MatchRatio()}});
  return refined;
}

}  // namespace

nlohmann::json ToJson(const IterationRecord& r) {
  const LocalisationResult* localisation = r.localisation ? &*r.localisation : nullptr;
  const double evaluate_s = localisation ? localisation->evaluate_s : 0.0;
  const double refine_s = localisation ? localisation->refine_s : 0.0;
  nlohmann::json out = {{"index", r.index},
                        {"timestamp_s", r.timestamp_s},
                        {"origin", r.origin},
                        {"skipped", r.skipped},
                        {"first", r.first},
                        {"prediction", ToJson(r.prediction)},
                        {"T_world_robot", ToJson(r.T_world_robot)},
                        {"validated", r.validated},
                        {"reason", ToString(r.verdict)},
                        {"inserted", r.inserted},
                        {"carved", r.carved},
                        {"map_points", r.map_points},
                        {"timings_ms",
                         {{"evaluate", 1e3 * evaluate_s},
                          {"refine", 1e3 * refine_s},
                          {"insert", 1e3 * r.insert_s},
                          {"total", 1e3 * r.total_s}}}};
  const RankedCandidate* kept = r.Kept();
  if (localisation && !localisation->evaluated.empty()) {
    out["candidates"] = EvaluatedToJson(*localisation)["candidates"];
    out["chosen"] = kept ? nlohmann::json(kept->candidate.label) : nlohmann::json(nullptr);
    out["problems"] = localisation->problems;
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

RunFolder::RunFolder(const std::string& directory) : directory_(directory) {
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
  trajectory_.push_back({record.timestamp_s, record.T_world_robot});
}

void RunFolder::Finish(const PointMap& map, nlohmann::json summary) {
  records_.close();
  WriteTumTrajectory(Path("trajectory.tum"), trajectory_);
  SavePointMapPcd(map, Path("map.pcd"));
  summary["files"] = {
      {"iterations", "iterations.jsonl"}, {"trajectory", "trajectory.tum"}, {"map", "map.pcd"}};
  WriteFileAtomically(Path("summary.json"),
                      [&](std::ostream& out) { out << summary.dump(2) << '\n'; });
}

}  // namespace scanloc
