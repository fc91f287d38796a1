#pragma once
// Run folders set side by side (`scanloc compare --runs`): the same log localised on a line map and
// on a scan map of the same place (the mission's line-map versus scan-map comparison), or a
// localisation beside the session that built its map. For each run: what it confirmed, its
// moments, its cost; for each run after the first: how far its postures lie from the first's at
// the same scans.

#include <iosfwd>
#include <optional>
#include <string>
#include <vector>

namespace scanloc {

struct RunSide {
  std::string directory;
  std::string map;  // the inputs it localised on: "line map", "point map", "both", "grown"
  std::size_t scans = 0, localised = 0, validated = 0, posed = 0;
  std::optional<std::size_t> first_confirmed;  // localise runs
  double mean_expect_value_m = 0.0;            // over the validated scans' final Likelihood Tests
  double mean_match_ratio = 0.0;
  double mean_iteration_ms = 0.0;
  // Against the first run, over the scans both gave a posture (by timestamp): median and maximum
  // distance, and how many were compared. Unset for the first run.
  std::optional<double> median_distance_m, max_distance_m;
  std::size_t compared = 0;
};

// Reads each run folder (errors name the folder and what was missing).
std::vector<RunSide> CompareRuns(const std::vector<std::string>& directories);

void PrintRunComparison(std::ostream& out, const std::vector<RunSide>& sides);

}  // namespace scanloc
