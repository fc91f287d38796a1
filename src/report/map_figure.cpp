#include "scanloc/report/map_figure.hpp"

#include <algorithm>
#include <cmath>
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

constexpr double kWidthPx = 600.0, kPlotHeightPx = 470.0;
constexpr double kCloseUpPx = 420.0;
constexpr double kArrowPx = 34.0, kChosenArrowPx = 42.0;
// Long arrows in the close-up: candidates 5° apart have their tips 11 px apart.
constexpr double kCloseUpArrowPx = 130.0, kCloseUpChosenArrowPx = 140.0;
constexpr double kLabelFontPx = 11.0;
// The view keeps this share of the scan's points in each axis (a few far returns through a door
// or window would otherwise shrink everything else), grows by kPadding on each side and spans at
// least kMinViewM.
constexpr double kScanQuantile = 0.02;
constexpr double kPadding = 0.08;
constexpr double kMinViewM = 4.0;
// Without a scan or candidates: this far around the kept posture.
constexpr double kDefaultViewM = 16.0;
// The close-up spans the candidates with this padding, and at least kCloseUpMinViewM.
constexpr double kCloseUpPadding = 0.3;
constexpr double kCloseUpMinViewM = 5.0;

std::vector<Eigen::Vector2d> ScanPointsWorld(const LaserScan& scan, const Pose2D& T_world_laser) {
  std::vector<Eigen::Vector2d> points;
  for (std::size_t i = 0; i < scan.size(); ++i)
    if (scan.IsValid(i)) points.push_back(T_world_laser.Transform(scan.Point(i)));
  return points;
}

std::string CandidateTooltip(const CandidateRow& c, bool chosen) {
  std::string text =
      c.label + (chosen ? " (chosen)" : "") + ": " +
      (c.valid ? "valid, rank " + std::to_string(c.rank) : c.reason) + "\nx " +
      FormatFixed(c.T_world_robot.x_m, 3) + " m, y " + FormatFixed(c.T_world_robot.y_m, 3) +
      " m, \xCE\xB8 " + FormatFixed(c.T_world_robot.yaw_rad, 4) + " rad\nMP " +
      std::to_string(c.test.match_pairs) + " / NVP " + std::to_string(c.test.valid_pairs) +
      ", EV " + FormatFixed(100.0 * c.test.expect_value_m, 2) + " cm";
  if (c.cost) text += ", cost " + FormatFixed(*c.cost, 4);
  return text;
}

}  // namespace

Pose2D ScanDrawnAt(const IterationRow& row, const LaserMounting& mounting) {
  return row.refinement ? row.refinement->T_world_laser : mounting.LaserPose(row.T_world_robot);
}

namespace {

// The part of the world drawn: the scan (its central part) and every posture of the iteration,
// or in the close-up the postures alone.
Box ViewOf(const IterationRow& row, const std::vector<Eigen::Vector2d>& scan_world, bool close_up) {
  Box view = close_up ? Box{} : CentralBox(scan_world, kScanQuantile);
  for (const CandidateRow& c : row.candidates) view.Extend(c.T_world_robot.Translation());
  view.Extend(row.T_world_robot.Translation());
  view.Extend(row.prediction.Translation());
  if (row.refinement) view.Extend(row.refinement->T_world_laser.Translation());
  if (close_up) return view.Padded(kCloseUpPadding, kCloseUpMinViewM);
  return view.Padded(kPadding,
                     scan_world.empty() && row.candidates.empty() ? kDefaultViewM : kMinViewM);
}

std::vector<LegendItem> LegendOf(const IterationFigureInput& input, bool has_lines) {
  const IterationRow& row = *input.row;
  std::vector<LegendItem> legend = {{LegendItem::Symbol::kDot, style::kMapPoint, input.map_label}};
  if (has_lines) legend.push_back({LegendItem::Symbol::kLine, style::kLineMap, "line map"});
  if (input.scan)
    legend.push_back({LegendItem::Symbol::kDot, style::kScan,
                      row.refinement ? "scan at the refined posture" : "scan at the kept posture"});
  if (!row.candidates.empty()) {
    legend.push_back({LegendItem::Symbol::kArrow, style::kValid, "valid candidate"});
    legend.push_back({LegendItem::Symbol::kArrow, style::kInvalid, "invalid candidate"});
  }
  if (row.refinement)
    legend.push_back({LegendItem::Symbol::kArrow, style::kRefined, "chosen, refined"});
  legend.push_back({LegendItem::Symbol::kRing, "#000", "odometry prediction"});
  return legend;
}

// The map's points and lines, then the scan, clipped to the plot; false when no map shows.
bool DrawMapAndScan(SvgCanvas& svg, const MapFrame& frame, const IterationFigureInput& input,
                    const std::vector<Eigen::Vector2d>& scan_world, double width,
                    double plot_height, bool close_up) {
  const bool has_lines = input.line_map && !input.line_map->empty();
  svg.BeginClippedGroup(0, 0, width, plot_height);
  std::vector<Eigen::Vector2d> pixels;
  if (input.map_points)
    for (const Eigen::Vector2d& p : *input.map_points) {
      const Eigen::Vector2d px = frame.ToPixel(p);
      if (frame.Inside(px, 2.0)) pixels.push_back(px);
    }
  svg.Dots(pixels, close_up ? 3.2 : 2.0, style::kMapPoint);
  const bool map_shown = !pixels.empty() || has_lines;
  if (has_lines)
    for (const Segment& s : input.line_map->segments)
      svg.Line(frame.ToPixel(s.a), frame.ToPixel(s.b), style::kLineMap, 1.3);
  pixels.clear();
  for (const Eigen::Vector2d& p : scan_world) pixels.push_back(frame.ToPixel(p));
  svg.Dots(pixels, close_up ? 3.6 : 2.6, style::kScan);
  svg.EndGroup();
  return map_shown;
}

struct PendingLabel {
  Eigen::Vector2d anchor;
  std::string text, colour;
  bool bold;
};

// The odometry prediction, then the candidates (the chosen one last, on top), then the refined
// posture; returns the candidates' labels, to be placed once every arrow is drawn.
std::vector<PendingLabel> DrawPostures(SvgCanvas& svg, const MapFrame& frame,
                                       const IterationRow& row, LabelPlacer& labels,
                                       double arrow_px, double chosen_arrow_px) {
  const Eigen::Vector2d prediction = frame.ToPixel(row.prediction.Translation());
  svg.BeginGroup("odometry prediction: x " + FormatFixed(row.prediction.x_m, 3) + " m, y " +
                 FormatFixed(row.prediction.y_m, 3) + " m, \xCE\xB8 " +
                 FormatFixed(row.prediction.yaw_rad, 4) + " rad");
  svg.Circle(prediction, 5.0, "none", "#000", 1.5);
  svg.EndGroup();
  labels.Reserve(prediction.x() - 5, prediction.y() - 5, 10, 10);
  std::vector<const CandidateRow*> order;
  for (const CandidateRow& c : row.candidates)
    if (c.label != row.chosen) order.push_back(&c);
  if (const CandidateRow* chosen = row.chosen_candidate()) order.push_back(chosen);
  std::vector<PendingLabel> pending;
  for (const CandidateRow* c : order) {
    const bool chosen = c->label == row.chosen;
    const char* colour = c->valid ? style::kValid : style::kInvalid;
    const double length = chosen ? chosen_arrow_px : arrow_px;
    const Eigen::Vector2d tail = frame.ToPixel(c->T_world_robot.Translation());
    const double heading = c->T_world_robot.yaw_rad;
    svg.BeginGroup(CandidateTooltip(*c, chosen));
    svg.Arrow(tail, heading, length, colour, chosen ? 2.6 : 1.6);
    svg.EndGroup();
    const Eigen::Vector2d direction(std::cos(heading), -std::sin(heading));
    const Eigen::Vector2d tip = tail + length * direction;
    labels.Reserve(tip.x() - 4, tip.y() - 4, 8, 8);  // no label over an arrow head
    pending.push_back({tail + (length + 6) * direction, c->label, colour, chosen});
  }
  if (row.refinement) {
    const Pose2D refined = row.refinement->T_world_laser;
    const Eigen::Vector2d tail = frame.ToPixel(refined.Translation());
    svg.BeginGroup("refined posture of the laser: x " + FormatFixed(refined.x_m, 3) + " m, y " +
                   FormatFixed(refined.y_m, 3) + " m, \xCE\xB8 " + FormatFixed(refined.yaw_rad, 4) +
                   " rad");
    svg.Arrow(tail, refined.yaw_rad, chosen_arrow_px, style::kRefined, 2.0);
    svg.EndGroup();
  }
  return pending;
}

// Labels last, so that no arrow hides one; the chosen candidate's first, so that it is placed.
void PlaceLabels(SvgCanvas& svg, std::vector<PendingLabel> pending, LabelPlacer& labels) {
  std::stable_partition(pending.begin(), pending.end(),
                        [](const PendingLabel& l) { return l.bold; });
  for (const PendingLabel& l : pending)
    if (const auto at = labels.Place(l.anchor, l.text, kLabelFontPx)) {
      svg.Rect(at->x() - 1, at->y() - 0.8 * kLabelFontPx - 1,
               EstimateTextWidth(l.text, kLabelFontPx) + 2, kLabelFontPx + 3, "white");
      svg.Text(*at, l.text, {kLabelFontPx, "start", l.colour, l.bold});
    }
}

}  // namespace

std::string IterationMapFigure(const IterationFigureInput& input, const std::string& id) {
  if (!input.row) throw std::invalid_argument("IterationMapFigure: no iteration given");
  const IterationRow& row = *input.row;
  const Pose2D T_world_laser = ScanDrawnAt(row, input.mounting);
  const std::vector<Eigen::Vector2d> scan_world =
      input.scan ? ScanPointsWorld(*input.scan, T_world_laser) : std::vector<Eigen::Vector2d>{};
  const bool close_up = input.view == IterationView::kCandidates;
  const double width = close_up ? kCloseUpPx : kWidthPx;
  const double plot_height = close_up ? kCloseUpPx : kPlotHeightPx;
  const bool has_lines = input.line_map && !input.line_map->empty();
  const std::vector<LegendItem> legend = LegendOf(input, has_lines);
  const double legend_height = close_up ? 0.0 : LegendHeight(legend, width - 16) + 10;

  SvgCanvas svg(width, plot_height + legend_height, id,
                "iteration " + std::to_string(row.index) +
                    (close_up ? ": close-up of the candidates" : " on the map"));
  const MapFrame frame(ViewOf(row, scan_world, close_up), 0, 0, width, plot_height);
  svg.Rect(0, 0, width, plot_height, "white", style::kFrame, 1.0);
  LabelPlacer labels(2, 2, width - 4, plot_height - 4);
  const bool map_shown =
      DrawMapAndScan(svg, frame, input, scan_world, width, plot_height, close_up);
  std::vector<PendingLabel> pending =
      DrawPostures(svg, frame, row, labels, close_up ? kCloseUpArrowPx : kArrowPx,
                   close_up ? kCloseUpChosenArrowPx : kChosenArrowPx);
  DrawScaleBar(svg, frame, &labels);
  PlaceLabels(svg, std::move(pending), labels);

  std::string message;
  if (!input.scan) message = "scan unavailable";
  if (!map_shown) message += std::string(message.empty() ? "" : "; ") + "no map in this view";
  if (!message.empty()) svg.Text({width / 2, 20}, message, {13.0, "middle", style::kMessage, true});
  if (!close_up) DrawLegend(svg, legend, 8, plot_height + 14, width - 16);
  return svg.Finish();
}

}  // namespace scanloc
