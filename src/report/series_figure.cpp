#include "scanloc/report/series_figure.hpp"

#include <algorithm>

#include "scanloc/report/figure_style.hpp"
#include "scanloc/report/legend.hpp"
#include "scanloc/report/markup.hpp"
#include "scanloc/report/plot_frame.hpp"
#include "scanloc/report/svg_canvas.hpp"

namespace scanloc {
namespace {

constexpr char kSignatureColour[] = "#7b4fb0";

namespace style = figure_style;

const TwoPanelLayout kLayout;
const double kPanelHeightPx = kLayout.panel_height_px;
// The EV panel spans up to this multiple of E_max, or the 98th percentile of EV when that is
// lower (larger values are drawn on the top edge).
constexpr double kEvSpanOfMax = 4.0;

struct Panel {
  std::string title, unit;
  LinearAxis y;
  double threshold;
  std::vector<double> ticks;
  int decimals;
};

}  // namespace

const LikelihoodTestResult* FinalTest(const IterationRow& row) {
  if (row.refinement) return &row.refinement->after;
  if (const CandidateRow* chosen = row.chosen_candidate()) return &chosen->test;
  return nullptr;
}

namespace {

// The laser signature's bound over the session, (iteration, cm), where the records carry it
// (sessions since issue 15).
std::vector<std::pair<double, double>> SignatureSeriesCm(const std::vector<IterationRow>& rows) {
  std::vector<std::pair<double, double>> series;
  for (const IterationRow& row : rows)
    if (row.signature_expect_value_m)
      series.emplace_back(static_cast<double>(row.index), 100.0 * *row.signature_expect_value_m);
  return series;
}

std::vector<LegendItem> MomentLegend(bool with_signature) {
  std::vector<LegendItem> legend = {
      {LegendItem::Symbol::kDot, style::kValid, "validated"},
      {LegendItem::Symbol::kDot, style::kInvalid, "flagged (not validated)"},
      {LegendItem::Symbol::kDashedLine, style::kAxis, "threshold of rule 2 (E_max) / rule 1"}};
  if (with_signature)
    legend.push_back({LegendItem::Symbol::kLine, kSignatureColour, "laser signature's E_max"});
  return legend;
}

}  // namespace

std::string MomentSeriesFigure(const std::vector<IterationRow>& rows,
                               const ValidationOptions& validation, const std::string& id) {
  struct Sample {
    double index, ev_cm, ratio;
    bool validated;
  };
  std::vector<Sample> samples;
  for (const IterationRow& row : rows)
    if (const LikelihoodTestResult* test = FinalTest(row))
      samples.push_back({static_cast<double>(row.index), 100.0 * test->expect_value_m,
                         test->MatchRatio(), row.validated});

  const std::vector<std::pair<double, double>> signature_cm = SignatureSeriesCm(rows);
  const std::vector<LegendItem> legend = MomentLegend(!signature_cm.empty());
  const double plot_x0 = kLayout.x0(), plot_x1 = kLayout.x1();
  SvgCanvas svg = TwoPanelCanvas(kLayout, legend, id, "moments over the session");
  if (samples.empty())
    return FinishEmpty(svg, kLayout, "no iteration was localised: no moments to draw");
  const double e_max_cm = 100.0 * validation.max_expect_value_m;
  std::vector<double> evs;
  for (const Sample& s : samples) evs.push_back(s.ev_cm);
  std::sort(evs.begin(), evs.end());
  double ev_high = std::max(
      1.2 * e_max_cm, std::min(kEvSpanOfMax * e_max_cm, evs[(evs.size() - 1) * 98 / 100] * 1.05));
  for (const auto& sample : signature_cm) ev_high = std::max(ev_high, 1.05 * sample.second);
  const double last_index = rows.empty() ? 1.0 : std::max<double>(1.0, rows.back().index);
  const LinearAxis x{0.0, last_index, plot_x0 + 4, plot_x1 - 4};

  for (int p = 0; p < 2; ++p) {
    const double top = kLayout.PanelTop(p);
    const double bottom = top + kPanelHeightPx;
    Panel panel = p == 0 ? Panel{"EV [cm]",
                                 "cm",
                                 {0.0, ev_high, bottom, top},
                                 e_max_cm,
                                 NiceTicks(0.0, ev_high, 4),
                                 1}
                         : Panel{"MP/NVP",
                                 "",
                                 {0.0, 1.0, bottom, top},
                                 validation.min_match_ratio,
                                 NiceTicks(0.0, 1.0, 4),
                                 1};
    svg.Rect(plot_x0, top, plot_x1 - plot_x0, kPanelHeightPx, "white", style::kFrame, 0.8);
    for (const double t : panel.ticks) {
      svg.Line({plot_x0, panel.y(t)}, {plot_x1, panel.y(t)}, style::kGrid, 0.8);
      svg.Text({plot_x0 - 5, panel.y(t) + 4}, FormatFixed(t, panel.decimals),
               {10.0, "end", style::kAxis});
    }
    svg.Text({14, top + kPanelHeightPx / 2}, panel.title, {11.0, "start", "#222", true});
    std::vector<Eigen::Vector2d> valid, flagged;
    for (const Sample& s : samples) {
      const double value = p == 0 ? s.ev_cm : s.ratio;
      const Eigen::Vector2d at(x(s.index), std::clamp(panel.y(value), top + 1, bottom - 1));
      (s.validated ? valid : flagged).push_back(at);
    }
    svg.Dots(valid, 3.0, style::kValid);
    svg.Dots(flagged, 3.0, style::kInvalid);
    svg.Line({plot_x0, panel.y(panel.threshold)}, {plot_x1, panel.y(panel.threshold)}, style::kAxis,
             1.2, "5 4");
    if (p == 0 && !signature_cm.empty()) {
      std::vector<Eigen::Vector2d> line;
      for (const auto& [index, cm] : signature_cm)
        line.emplace_back(x(index), std::clamp(panel.y(cm), top + 1, bottom - 1));
      svg.Polyline(line, kSignatureColour, 1.2);
    }
  }
  DrawIterationAxis(svg, x, last_index, kLayout.AxisY(), plot_x0, plot_x1);
  DrawLegendBelow(svg, kLayout, legend);
  return svg.Finish();
}

}  // namespace scanloc
