#pragma once
// A session's run folder: iterations.jsonl (one record per iteration, written as it happens),
// and at the end trajectory.tum, map.pcd and summary.json, each written whole or not at all, so an
// interrupted session still leaves every file complete and readable.

#include <fstream>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "scanloc/io/trajectory.hpp"
#include "scanloc/maps/point_map.hpp"
#include "scanloc/session/session.hpp"

namespace scanloc {

nlohmann::json ToJson(const IterationRecord& record);

class RunFolder {
 public:
  // Creates the folder (and parents) if needed; throws std::runtime_error naming it otherwise.
  explicit RunFolder(const std::string& directory);
  RunFolder(const RunFolder&) = delete;
  RunFolder& operator=(const RunFolder&) = delete;

  // Appends one complete line to iterations.jsonl and remembers the posture for the trajectory.
  void Record(const IterationRecord& record);
  // Writes trajectory.tum, map.pcd and summary.json (the given summary plus file names).
  void Finish(const PointMap& map, nlohmann::json summary);

  const std::string& directory() const { return directory_; }
  std::string Path(const std::string& name) const { return directory_ + "/" + name; }

 private:
  std::string directory_;
  std::ofstream records_;
  std::vector<StampedPose> trajectory_;
};

}  // namespace scanloc
