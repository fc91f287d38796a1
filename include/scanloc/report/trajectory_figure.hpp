#pragma once
// The session's trajectory over its final map: the postures kept for every iteration, the
// flagged ones marked, and the iterations the report draws in detail linked to their sections.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "scanloc/maps/line_map.hpp"
#include "scanloc/report/run_records.hpp"

namespace scanloc {

class SvgCanvas;
class MapFrame;

struct TrajectoryFigureInput {
  const std::vector<IterationRow>* rows = nullptr;           // required
  const std::vector<Eigen::Vector2d>* map_points = nullptr;  // the final map; may be empty
  const LineMap* line_map = nullptr;                         // may be nullptr or empty
  std::vector<std::size_t> linked;  // iterations with a section "#iteration-N" on the page
  bool close_up = false;            // span the trajectory only, not the whole map
};

// `id` must be unique in the page.
std::string TrajectoryFigure(const TrajectoryFigureInput& input, const std::string& id);

// Each accepted loop closure, a line from the old scan's posture to the closing scan's (for this
// figure and the one over the grid).
void DrawClosures(SvgCanvas& svg, const MapFrame& frame, const std::vector<IterationRow>& rows);
// True when a row carries an accepted loop closure.
bool HasClosures(const std::vector<IterationRow>& rows);

// True when the trajectory spans less than a third of the whole map's view, so that a close-up
// shows what the whole view cannot.
bool TrajectoryCloseUpWorthwhile(const TrajectoryFigureInput& input);

}  // namespace scanloc
