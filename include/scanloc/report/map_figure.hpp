#pragma once
// One iteration on the map, as the chapter's Figures 10 and 19 show it: the map, the candidate
// postures as arrows (valid green, invalid red, labelled), the refined posture, and the scan drawn
// at the chosen posture.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/maps/line_map.hpp"
#include "scanloc/report/run_records.hpp"

namespace scanloc {

// What the figure spans: the whole scan, or a close-up of the candidates (where postures a few
// degrees apart can be told from each other).
enum class IterationView { kScan, kCandidates };

struct IterationFigureInput {
  const IterationRow* row = nullptr;                         // required
  const std::vector<Eigen::Vector2d>* map_points = nullptr;  // world; may be empty
  const LineMap* line_map = nullptr;                         // may be nullptr or empty
  const LaserScan* scan = nullptr;                           // nullptr when unavailable
  LaserMounting mounting;         // for the scan at the kept posture when nothing was refined
  std::string map_label = "map";  // what the grey points are, for the legend
  IterationView view = IterationView::kScan;
};

// T_world_laser the scan is drawn from: the chosen candidate's refined posture when there is one,
// else the posture kept for the iteration.
Pose2D ScanDrawnAt(const IterationRow& row, const LaserMounting& mounting);

// The figure as an <svg> element; `id` must be unique in the page. The close-up has no legend
// (its symbols are the overview's).
std::string IterationMapFigure(const IterationFigureInput& input, const std::string& id);

}  // namespace scanloc
