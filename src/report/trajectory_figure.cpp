#include "scanloc/report/trajectory_figure.hpp"

#include <algorithm>
#include <optional>
#include <stdexcept>

#include "scanloc/report/figure_style.hpp"
#include "scanloc/report/label_placer.hpp"
#include "scanloc/report/legend.hpp"
#include "scanloc/report/markup.hpp"
#include "scanloc/report/plot_frame.hpp"
#include "scanloc/report/svg_canvas.hpp"

namespace scanloc {
namespace {

namespace style = figure_style;

constexpr double kWidthPx = 640.0, kPlotHeightPx = 540.0;
// Map points outside the central share in either axis do not widen the view (stray far returns).
constexpr double kMapQuantile = 0.005;
constexpr double kPadding = 0.04;
constexpr double kMinViewM = 4.0;
constexpr double kCloseUpPadding = 0.1;
constexpr double kCloseUpShare = 1.0 / 3.0;

Box TrajectoryBox(const std::vector<IterationRow>& rows) {
  Box box;
  for (const IterationRow& row : rows) box.Extend(row.T_world_robot.Translation());
  return box;
}

// The view spanning the final map, the line map and the trajectory.
Box WholeView(const TrajectoryFigureInput& input) {
  Box view = input.map_points && !input.map_points->empty()
                 ? CentralBox(*input.map_points, kMapQuantile)
                 : Box{};
  for (const IterationRow& row : *input.rows) view.Extend(row.T_world_robot.Translation());
  if (input.line_map)
    for (const Segment& s : input.line_map->segments) {
      view.Extend(s.a);
      view.Extend(s.b);
    }
  if (view.empty()) view.Extend({0.0, 0.0});
  return view.Padded(kPadding, kMinViewM);
}

// The start and end of the trajectory, squares with their names.
void MarkStartAndEnd(SvgCanvas& svg, LabelPlacer& labels, const Eigen::Vector2d& start,
                     const Eigen::Vector2d& end) {
  svg.Rect(start.x() - 4, start.y() - 4, 8, 8, style::kValid);
  svg.Text({start.x() + 7, start.y() - 7}, "start", {11.0, "start", "#222", true});
  svg.Rect(end.x() - 4, end.y() - 4, 8, 8, "#000");
  svg.Text({end.x() + 7, end.y() + 14}, "end", {11.0, "start", "#222", true});
  labels.Reserve(start.x() + 5, start.y() - 18, 34, 14);
  labels.Reserve(end.x() + 5, end.y() + 3, 26, 14);
}

}  // namespace

void DrawClosures(SvgCanvas& svg, const MapFrame& frame, const std::vector<IterationRow>& rows) {
  for (const IterationRow& row : rows)
    if (const std::optional<std::size_t> old = row.closed_with(); old && *old < rows.size())
      svg.Line(frame.ToPixel(rows[*old].T_world_robot.Translation()),
               frame.ToPixel(row.T_world_robot.Translation()), style::kClosure, 1.6);
}

bool HasClosures(const std::vector<IterationRow>& rows) {
  return std::any_of(rows.begin(), rows.end(),
                     [](const IterationRow& row) { return row.closed_with().has_value(); });
}

bool TrajectoryCloseUpWorthwhile(const TrajectoryFigureInput& input) {
  if (!input.rows || input.rows->empty()) return false;
  const Box trajectory = TrajectoryBox(*input.rows).Padded(kCloseUpPadding, kMinViewM);
  const Box whole = WholeView(input);
  return (trajectory.max - trajectory.min).maxCoeff() <
         kCloseUpShare * (whole.max - whole.min).maxCoeff();
}

std::string TrajectoryFigure(const TrajectoryFigureInput& input, const std::string& id) {
  if (!input.rows) throw std::invalid_argument("TrajectoryFigure: no iterations given");
  const std::vector<IterationRow>& rows = *input.rows;
  const bool has_lines = input.line_map && !input.line_map->empty();
  const bool has_map = input.map_points && !input.map_points->empty();

  Box view = input.close_up ? TrajectoryBox(rows) : WholeView(input);
  if (input.close_up) {
    if (view.empty()) view.Extend({0.0, 0.0});
    view = view.Padded(kCloseUpPadding, kMinViewM);
  }

  std::vector<LegendItem> legend = {
      {LegendItem::Symbol::kDot, style::kMapPoint, "final map (map.pcd)"}};
  if (has_lines) legend.push_back({LegendItem::Symbol::kLine, style::kLineMap, "line map"});
  legend.push_back({LegendItem::Symbol::kLine, style::kTrajectory, "kept postures"});
  legend.push_back({LegendItem::Symbol::kDot, style::kInvalid, "flagged (not validated)"});
  if (HasClosures(rows))
    legend.push_back({LegendItem::Symbol::kLine, style::kClosure, "loop closures (accepted)"});
  legend.push_back({LegendItem::Symbol::kRing, "#000", "drawn below (click to go there)"});
  const double legend_height = LegendHeight(legend, kWidthPx - 16);

  SvgCanvas svg(kWidthPx, kPlotHeightPx + legend_height + 10, id,
                input.close_up ? "trajectory, close-up" : "trajectory over the final map");
  const MapFrame frame(view, 0, 0, kWidthPx, kPlotHeightPx);
  svg.Rect(0, 0, kWidthPx, kPlotHeightPx, "white", style::kFrame, 1.0);
  svg.BeginClippedGroup(0, 0, kWidthPx, kPlotHeightPx);
  std::vector<Eigen::Vector2d> pixels;
  if (has_map)
    for (const Eigen::Vector2d& p : *input.map_points) {
      const Eigen::Vector2d px = frame.ToPixel(p);
      if (frame.Inside(px, 2.0)) pixels.push_back(px);
    }
  svg.Dots(pixels, 1.6, style::kMapPoint);
  if (has_lines)
    for (const Segment& s : input.line_map->segments)
      svg.Line(frame.ToPixel(s.a), frame.ToPixel(s.b), style::kLineMap, 1.2);
  pixels.clear();
  std::vector<Eigen::Vector2d> flagged;
  for (const IterationRow& row : rows) {
    pixels.push_back(frame.ToPixel(row.T_world_robot.Translation()));
    if (row.flagged()) flagged.push_back(pixels.back());
  }
  svg.Polyline(pixels, style::kTrajectory, 1.6);
  DrawClosures(svg, frame, rows);
  svg.Dots(flagged, 4.0, style::kInvalid);
  svg.EndGroup();

  LabelPlacer labels(2, 2, kWidthPx - 4, kPlotHeightPx - 40);
  if (!rows.empty()) MarkStartAndEnd(svg, labels, pixels.front(), pixels.back());
  for (const std::size_t index : input.linked) {
    if (index >= rows.size()) continue;
    const IterationRow& row = rows[index];
    const Eigen::Vector2d at = frame.ToPixel(row.T_world_robot.Translation());
    svg.BeginLink("#iteration-" + std::to_string(index));
    svg.BeginGroup("iteration " + std::to_string(index) + ": " + row.status() +
                   (row.flagged() ? " (" + row.reason + ")" : ""));
    svg.Circle(at, 5.0, "white", "#000", 1.3);
    const std::string text = std::to_string(index);
    if (const auto place = labels.Place(at, text, 10.0))
      svg.Text(*place, text, {10.0, "start", "#000"});
    svg.EndGroup();
    svg.EndLink();
  }
  DrawScaleBar(svg, frame);
  if (!has_map && !has_lines)
    svg.Text({kWidthPx / 2, 24}, "the map is empty", {13.0, "middle", style::kMessage, true});
  DrawLegend(svg, legend, 8, kPlotHeightPx + 14, kWidthPx - 16);
  return svg.Finish();
}

}  // namespace scanloc
