#pragma once
// The session's trajectory over its occupancy grid, drawn a pixel per cell (an embedded PNG) so
// that a doubled wall shows when the page magnifies it: the kept postures at full precision, the
// flagged ones, the iterations drawn in detail as numbered rings linked to their sections, and
// labels only where they overlap no earlier one.

#include <string>

#include "scanloc/io/occupancy_grid_io.hpp"
#include "scanloc/report/trajectory_figure.hpp"

namespace scanloc {

struct GridTrajectoryFigure {
  std::string svg;     // the map, sized width_px × height_px at zoom 1
  std::string legend;  // a separate <svg>, so that it keeps its size when the map is zoomed
  double width_px = 0.0, height_px = 0.0;
};

// The grid fills at most max_width_px × max_height_px at zoom 1. Strokes, markers (circles in
// groups of class "marker", radius 5, and "flag", radius 2) and texts are meant to keep their size
// on screen when the page magnifies the figure (html_report's CSS). `id` must be unique in the
// page.
GridTrajectoryFigure TrajectoryOverGridFigure(const TrajectoryFigureInput& input,
                                              const OccupancyGridImage& grid, const std::string& id,
                                              double max_width_px = 960,
                                              double max_height_px = 800);

// The grid's pixels for the page: occupied dark, free white, unknown light grey.
std::vector<std::uint8_t> GridShades(const OccupancyGridImage& grid);

}  // namespace scanloc
