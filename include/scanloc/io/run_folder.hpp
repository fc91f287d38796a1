#pragma once
// A session's run folder: iterations.jsonl (one record per iteration, written as it happens),
// and at the end trajectory.tum, map.pcd, the occupancy grid (map.pgm + map.yaml) and summary.json,
// each written whole or not at all, so an interrupted session still leaves every file complete and
// readable.

#include <fstream>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "scanloc/io/trajectory.hpp"
#include "scanloc/maps/occupancy_grid.hpp"
#include "scanloc/maps/point_map.hpp"
#include "scanloc/session/session.hpp"

namespace scanloc {

nlohmann::json ToJson(const IterationRecord& record);

class RunFolder {
 public:
  // Creates the folder (and parents) if needed; throws std::runtime_error naming it when it
  // cannot, or when it exists with anything in it and `overwrite` is false (nothing is touched).
  explicit RunFolder(const std::string& directory, bool overwrite = false);
  RunFolder(const RunFolder&) = delete;
  RunFolder& operator=(const RunFolder&) = delete;

  // Appends one complete line to iterations.jsonl and remembers the posture for the trajectory
  // (a scan without one, a localisation still searching, is left out of it).
  void Record(const IterationRecord& record);
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
  std::string directory_;
  std::ofstream records_;
  std::vector<StampedPose> trajectory_;
  std::vector<std::size_t> trajectory_records_;  // the record index of each trajectory posture
  std::vector<StampedPose> online_trajectory_;   // before Correct, when it corrected anything
  bool wrote_graph_ = false;
};

}  // namespace scanloc
