#include "scanloc/report/grid_trajectory_figure.hpp"

#include <algorithm>
#include <stdexcept>

#include "scanloc/report/figure_style.hpp"
#include "scanloc/report/label_placer.hpp"
#include "scanloc/report/legend.hpp"
#include "scanloc/report/plot_frame.hpp"
#include "scanloc/report/png_image.hpp"
#include "scanloc/report/svg_canvas.hpp"

namespace scanloc {
namespace {

namespace style = figure_style;

// Coordinates to 0.001 px: at 16× a thousandth of a pixel is still far below a screen pixel.
constexpr int kDecimals = 3;
constexpr std::uint8_t kOccupiedShade = 40, kFreeShade = 255, kUnknownShade = 222;
constexpr double kRingRadiusPx = 5.0, kFlagRadiusPx = 2.0, kLabelSizePx = 10.0;
// The line map in a colour that stays visible over occupied (dark) cells.
constexpr const char* kLineMapOverGrid = "#c51b7d";

Box GridBox(const OccupancyGridImage& grid) {
  Box box;
  box.Extend(grid.origin_m);
  box.Extend(grid.origin_m + grid.resolution_m * Eigen::Vector2d(static_cast<double>(grid.width),
                                                                 static_cast<double>(grid.height)));
  return box;
}

// A marker on the path: its position, tooltip, link ("" for none) and label.
struct Marker {
  Eigen::Vector2d at;
  std::string tooltip, href, label;
  bool ring = true;  // a numbered ring; else a filled dot of `colour`
  const char* colour = "#000";
};

// The start, the end and the iterations drawn below (numbered rings linked to their sections).
std::vector<Marker> Markers(const MapFrame& frame, const TrajectoryFigureInput& input) {
  const std::vector<IterationRow>& rows = *input.rows;
  std::vector<Marker> markers;
  if (rows.empty()) return markers;
  markers.push_back({frame.ToPixel(rows.front().T_world_robot.Translation()), "start", "", "start",
                     false, style::kValid});
  markers.push_back(
      {frame.ToPixel(rows.back().T_world_robot.Translation()), "end", "", "end", false, "#000"});
  for (const std::size_t index : input.linked) {
    if (index >= rows.size()) continue;
    const IterationRow& row = rows[index];
    markers.push_back({frame.ToPixel(row.T_world_robot.Translation()),
                       "iteration " + std::to_string(index) + ": " + row.status() +
                           (row.flagged() ? " (" + row.reason + ")" : ""),
                       "#iteration-" + std::to_string(index), std::to_string(index)});
  }
  return markers;
}

// Every marker first, kept free of labels; then the labels, each beside its marker or left out
// when that would cover an earlier one (where the path returns); the marker keeps its tooltip.
void DrawMarkers(SvgCanvas& svg, const std::vector<Marker>& markers, LabelPlacer& labels) {
  std::vector<const Marker*> drawing_order;  // the rings, then the start and end dots over them
  for (const bool ring : {true, false})
    for (const Marker& m : markers)
      if (m.ring == ring) drawing_order.push_back(&m);
  for (const Marker* marker : drawing_order) {
    const Marker& m = *marker;
    if (!m.href.empty()) svg.BeginLink(m.href);
    svg.BeginGroup(m.tooltip, "marker");
    if (m.ring)
      svg.Circle(m.at, kRingRadiusPx, "white", "#000", 1.3);
    else
      svg.Circle(m.at, kRingRadiusPx, m.colour);
    svg.EndGroup();
    if (!m.href.empty()) svg.EndLink();
    // Inside the label's gap (LabelPlacer's 4 px), so that a label beside its own ring fits.
    constexpr double kKeptFreePx = 3.5;
    labels.Reserve(m.at.x() - kKeptFreePx, m.at.y() - kKeptFreePx, 2 * kKeptFreePx,
                   2 * kKeptFreePx);
  }
  for (const Marker& m : markers) {
    const auto place = labels.Place(m.at, m.label, kLabelSizePx);
    if (!place) continue;
    if (!m.href.empty()) svg.BeginLink(m.href);
    svg.Text(*place, m.label, {kLabelSizePx, "start", "#000", !m.ring});
    if (!m.href.empty()) svg.EndLink();
  }
}

void DrawPath(SvgCanvas& svg, const MapFrame& frame, const TrajectoryFigureInput& input,
              LabelPlacer& labels) {
  std::vector<Eigen::Vector2d> pixels, flagged;
  for (const IterationRow& row : *input.rows) {
    pixels.push_back(frame.ToPixel(row.T_world_robot.Translation()));
    if (row.flagged()) flagged.push_back(pixels.back());
  }
  svg.Polyline(pixels, style::kTrajectory, 2.0);
  DrawClosures(svg, frame, *input.rows);
  // Circles at their exact place (Dots would snap them to a 2 px lattice, 32 px at 16×).
  svg.BeginGroup("", "flag");
  for (const Eigen::Vector2d& p : flagged) svg.Circle(p, kFlagRadiusPx, style::kInvalid);
  svg.EndGroup();
  DrawMarkers(svg, Markers(frame, input), labels);
}

std::string Legend(const TrajectoryFigureInput& input, double width_px) {
  std::vector<LegendItem> legend = {
      {LegendItem::Symbol::kDot, "#282828", "occupied cell (map.pgm)"}};
  if (input.line_map && !input.line_map->empty())
    legend.push_back({LegendItem::Symbol::kLine, kLineMapOverGrid, "line map"});
  legend.push_back({LegendItem::Symbol::kLine, style::kTrajectory, "kept postures"});
  legend.push_back({LegendItem::Symbol::kDot, style::kInvalid, "flagged (not validated)"});
  if (HasClosures(*input.rows))
    legend.push_back({LegendItem::Symbol::kLine, style::kClosure, "loop closures (accepted)"});
  legend.push_back({LegendItem::Symbol::kRing, "#000", "drawn below (click to go there)"});
  const double height = LegendHeight(legend, width_px - 16);
  SvgCanvas svg(width_px, height + 8, "legend", "legend");
  DrawLegend(svg, legend, 8, 12, width_px - 16);
  return svg.Finish();
}

}  // namespace

std::vector<std::uint8_t> GridShades(const OccupancyGridImage& grid) {
  std::vector<std::uint8_t> shades(grid.pixels.size());
  std::transform(grid.pixels.begin(), grid.pixels.end(), shades.begin(), [](unsigned char p) {
    return p == kPgmOccupied ? kOccupiedShade : p == kPgmFree ? kFreeShade : kUnknownShade;
  });
  return shades;
}

GridTrajectoryFigure TrajectoryOverGridFigure(const TrajectoryFigureInput& input,
                                              const OccupancyGridImage& grid, const std::string& id,
                                              double max_width_px, double max_height_px) {
  if (!input.rows) throw std::invalid_argument("TrajectoryOverGridFigure: no iterations given");
  if (grid.width == 0 || grid.height == 0 || grid.pixels.size() != grid.width * grid.height)
    throw std::invalid_argument("TrajectoryOverGridFigure: the grid has no cells");
  const double scale = std::min(max_width_px / grid.width, max_height_px / grid.height);
  GridTrajectoryFigure figure;
  figure.width_px = scale * grid.width;
  figure.height_px = scale * grid.height;
  SvgCanvas svg(figure.width_px, figure.height_px, id, "trajectory over the occupancy grid");
  svg.set_decimals(kDecimals);
  const MapFrame frame(GridBox(grid), 0, 0, figure.width_px, figure.height_px);
  svg.Image(0, 0, figure.width_px, figure.height_px,
            GreyscalePngDataUri(grid.width, grid.height, GridShades(grid)));
  if (input.line_map)
    for (const Segment& s : input.line_map->segments)
      svg.Line(frame.ToPixel(s.a), frame.ToPixel(s.b), kLineMapOverGrid, 1.0);
  LabelPlacer labels(2, 2, figure.width_px - 4, figure.height_px - 4, /*rings=*/1);
  DrawScaleBar(svg, frame, &labels);
  DrawPath(svg, frame, input, labels);
  svg.Rect(0, 0, figure.width_px, figure.height_px, "none", style::kFrame, 1.0);
  figure.svg = svg.Finish();
  figure.legend = Legend(input, std::min(figure.width_px, 640.0));
  return figure;
}

}  // namespace scanloc
