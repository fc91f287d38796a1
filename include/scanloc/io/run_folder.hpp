#pragma once
// A session's run folder: run.json (what the run was started with), iterations.jsonl (one record
// per iteration, written as it happens), and at the end trajectory.tum, map.pcd, the occupancy
// grid (map.pgm + map.yaml) and summary.json, each written whole or not at all, so an interrupted
// session still leaves every file complete and readable. A run folder opened to resume keeps its
// complete records, and the session goes on appending to them.

#include <fstream>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "scanloc/io/run_resume.hpp"
#include "scanloc/io/trajectory.hpp"
#include "scanloc/maps/occupancy_grid.hpp"
#include "scanloc/maps/point_map.hpp"
#include "scanloc/session/session.hpp"

namespace scanloc {

// The record's line of iterations.jsonl (without its newline), appended to `text`: the record
// format's one writer (keys: record_keys.hpp).
void WriteRecord(const IterationRecord& record, std::string& text);
// The same, parsed.
nlohmann::json ToJson(const IterationRecord& record);

enum class RunFolderOpening {
  kNew,        // a new or empty folder
  kOverwrite,  // any folder: the files of an earlier run in it are removed first
  kResume,     // the folder of an interrupted run: its complete records are read and kept
};

class RunFolder {
 public:
  // Creates the folder (and parents) if needed; throws std::runtime_error naming it when it
  // cannot, or when it exists with anything in it and `overwrite` is false (nothing is touched).
  explicit RunFolder(const std::string& directory, bool overwrite = false);
  // kResume throws when the folder holds no iterations.jsonl, ParseError when a complete line of
  // it is not a record; an incomplete last line is cut off.
  RunFolder(const std::string& directory, RunFolderOpening opening);
  RunFolder(const RunFolder&) = delete;
  RunFolder& operator=(const RunFolder&) = delete;

  // What the run is started with (inputs, configuration, options), as run.json. Resuming, the
  // folder's run.json must say the same: throws std::runtime_error naming what differs.
  void Begin(const nlohmann::json& identity);
  // The records read to resume (empty unless opened with kResume).
  const std::vector<RecordedIteration>& recorded() const { return recorded_; }
  // Appends one complete line to iterations.jsonl and remembers the posture for the trajectory
  // (a scan without one, a localisation still searching, is left out of it).
  void Record(const IterationRecord& record);
  // A replayed iteration, already in iterations.jsonl: its posture only is remembered.
  void Replayed(const IterationRecord& record);
  // Loop closure's corrections, by record index: the trajectory takes them, and the postures as
  // the session gave them go to trajectory-online.tum. Nothing happens when `postures` is empty.
  void Correct(const std::vector<std::optional<Pose2D>>& postures);
  // The pose graph, as graph.g2o.
  void WriteGraph(const PoseGraph& graph);
  // Writes trajectory.tum, map.pcd, map.pgm + map.yaml when `grid` is given, and summary.json
  // (the given summary plus file names), the summary last.
  void Finish(const PointMap& map, nlohmann::json summary, const OccupancyGrid* grid = nullptr);

  const std::string& directory() const { return directory_; }
  std::string Path(const std::string& name) const { return directory_ + "/" + name; }

 private:
  void Resume();

  std::string directory_;
  bool resuming_ = false;
  bool appended_ = false;  // a record was written by this process
  std::vector<RecordedIteration> recorded_;
  std::ofstream records_;
  std::string line_;  // the record being written; its capacity is reused
  std::vector<StampedPose> trajectory_;
  std::vector<std::size_t> trajectory_records_;  // the record index of each trajectory posture
  std::vector<StampedPose> online_trajectory_;   // before Correct, when it corrected anything
  bool wrote_graph_ = false;
};

}  // namespace scanloc
