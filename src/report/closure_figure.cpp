#include "scanloc/report/closure_figure.hpp"

#include <algorithm>
#include <cmath>

#include "scanloc/report/figure_style.hpp"
#include "scanloc/report/legend.hpp"
#include "scanloc/report/markup.hpp"
#include "scanloc/report/plot_frame.hpp"
#include "scanloc/report/svg_canvas.hpp"

namespace scanloc {
namespace {

namespace style = figure_style;

constexpr char kRejectedColour[] = "#9a9a9a";
// Panel titles stand above the panels.
const TwoPanelLayout kLayout{820.0, 130.0, 32.0, 56.0, 14.0, 22.0, 40.0};
const double kPanelHeightPx = kLayout.panel_height_px;

// One panel: its title, its value axis and the value each sample draws.
struct Panel {
  std::string title;
  LinearAxis y;
  std::vector<double> ticks;
  int decimals;
};

// The span of a panel: its largest value (the 98th percentile, so one wild closure does not
// flatten the rest; larger values are drawn on the edge), at least `floor`.
double Span(std::vector<double> values, double floor) {
  if (values.empty()) return floor;
  std::sort(values.begin(), values.end());
  return std::max(floor, 1.1 * values[(values.size() - 1) * 98 / 100]);
}

std::string Tooltip(const ClosureSample& s) {
  std::string text = "scan " + std::to_string(s.index) + " with scan " +
                     std::to_string(s.old_iteration) + (s.accepted ? ", accepted" : ", not accepted") +
                     ": " + FormatFixed(100.0 * s.shift_m, 1) + " cm, " +
                     FormatFixed(s.heading_rad * 180.0 / M_PI, 2) + "°";
  if (s.applied_m) text += "; the graph moved a node " + FormatFixed(100.0 * *s.applied_m, 1) + " cm";
  return text;
}

void DrawPanelFrame(SvgCanvas& svg, const Panel& panel, double top) {
  const double x0 = kLayout.x0(), x1 = kLayout.x1();
  svg.Rect(x0, top, x1 - x0, kPanelHeightPx, "white", style::kFrame, 0.8);
  for (const double t : panel.ticks) {
    svg.Line({x0, panel.y(t)}, {x1, panel.y(t)}, style::kGrid, 0.8);
    svg.Text({x0 - 5, panel.y(t) + 4}, FormatFixed(t, panel.decimals), {10.0, "end", style::kAxis});
  }
  svg.Text({x0, top - 6}, panel.title, {11.0, "start", "#222", true});  // above the panel
}

// The samples of one panel: the rejected first, so the accepted ones are drawn over them.
void DrawSamples(SvgCanvas& svg, const std::vector<ClosureSample>& samples, const LinearAxis& x,
                 const Panel& panel, double top, bool heading) {
  const double bottom = top + kPanelHeightPx;
  auto at = [&](double index, double value) {
    return Eigen::Vector2d(x(index), std::clamp(panel.y(value), top + 1, bottom - 1));
  };
  for (const bool accepted : {false, true})
    for (const ClosureSample& s : samples) {
      if (s.accepted != accepted) continue;
      const double index = static_cast<double>(s.index);
      svg.BeginGroup(Tooltip(s));
      if (!heading && s.applied_m)
        svg.Circle(at(index, 100.0 * *s.applied_m), 4.0, "none", style::kClosure, 1.2);
      const double value = heading ? s.heading_rad * 180.0 / M_PI : 100.0 * s.shift_m;
      svg.Circle(at(index, value), accepted ? 2.2 : 1.6, accepted ? style::kClosure : kRejectedColour);
      svg.EndGroup();
    }
}

std::vector<Panel> Panels(const std::vector<ClosureSample>& samples) {
  std::vector<double> shifts_cm, headings_deg;
  for (const ClosureSample& s : samples) {
    shifts_cm.push_back(100.0 * s.shift_m);
    if (s.applied_m) shifts_cm.push_back(100.0 * *s.applied_m);
    headings_deg.push_back(std::abs(s.heading_rad) * 180.0 / M_PI);
  }
  const double shift_high = Span(shifts_cm, 1.0), heading_high = Span(headings_deg, 0.5);
  std::vector<Panel> panels;
  for (int p = 0; p < 2; ++p) {
    const double top = kLayout.PanelTop(p), bottom = top + kPanelHeightPx;
    if (p == 0)
      panels.push_back({"shift [cm]", {0.0, shift_high, bottom, top},
                        NiceTicks(0.0, shift_high, 4), shift_high < 5.0 ? 1 : 0});
    else
      panels.push_back({"heading [°]", {-heading_high, heading_high, bottom, top},
                        NiceTicks(-heading_high, heading_high, 4), heading_high < 5.0 ? 1 : 0});
  }
  return panels;
}

}  // namespace

std::vector<ClosureSample> ClosureSamples(const std::vector<IterationRow>& rows) {
  std::vector<ClosureSample> samples;
  for (const IterationRow& row : rows) {
    if (!row.closure || !row.closure->T_world_robot_matched) continue;
    const Pose2D delta = Between(row.T_world_robot, *row.closure->T_world_robot_matched);
    ClosureSample s;
    s.index = row.index;
    s.old_iteration = row.closure->old_iteration;
    s.accepted = row.closure->accepted;
    s.shift_m = std::hypot(delta.x_m, delta.y_m);
    s.heading_rad = NormalizeAngle(delta.yaw_rad);
    if (s.accepted) s.applied_m = row.closure->largest_shift_m;
    samples.push_back(s);
  }
  return samples;
}

std::string ClosureCorrectionFigure(const std::vector<IterationRow>& rows, const std::string& id) {
  const std::vector<ClosureSample> samples = ClosureSamples(rows);
  const std::vector<LegendItem> legend = {
      {LegendItem::Symbol::kDot, style::kClosure, "accepted: the match against the old nodes"},
      {LegendItem::Symbol::kDot, kRejectedColour, "not accepted"},
      {LegendItem::Symbol::kRing, style::kClosure, "largest node shift of the solve that followed"}};
  const double plot_x0 = kLayout.x0(), plot_x1 = kLayout.x1();
  SvgCanvas svg = TwoPanelCanvas(kLayout, legend, id, "loop closures: the correction of each");
  if (samples.empty())
    return FinishEmpty(svg, kLayout, "no loop closure was matched: no correction to draw");
  const double last_index = std::max<double>(1.0, rows.back().index);
  const LinearAxis x{0.0, last_index, plot_x0 + 4, plot_x1 - 4};
  const std::vector<Panel> panels = Panels(samples);
  for (int p = 0; p < 2; ++p) {
    const double top = kLayout.PanelTop(p);
    DrawPanelFrame(svg, panels[p], top);
    DrawSamples(svg, samples, x, panels[p], top, p == 1);
  }
  DrawIterationAxis(svg, x, last_index, kLayout.AxisY(), plot_x0, plot_x1);
  DrawLegendBelow(svg, kLayout, legend);
  return svg.Finish();
}

}  // namespace scanloc
