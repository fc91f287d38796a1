#include "scanloc/report/histogram_figure.hpp"

#include <algorithm>
#include <cmath>

#include "scanloc/report/figure_style.hpp"
#include "scanloc/report/markup.hpp"
#include "scanloc/report/plot_frame.hpp"
#include "scanloc/report/svg_canvas.hpp"

namespace scanloc {
namespace {

namespace style = figure_style;

constexpr double kWidthPx = 470.0, kHeightPx = 270.0;
constexpr double kLeftPx = 48.0, kRightPx = 12.0, kTopPx = 46.0, kBottomPx = 42.0;
// Column widths as fractions of a slot: before wide in the back, after narrow in front.
constexpr double kBeforeWidth = 0.84, kAfterWidth = 0.5, kAloneWidth = 0.7;
constexpr double kSparkWidthPx = 84.0, kSparkHeightPx = 22.0;

std::string Moments(const char* stage, const LikelihoodTestResult& t) {
  return std::string(stage) + ": MP " + std::to_string(t.match_pairs) + " / NVP " +
         std::to_string(t.valid_pairs) + ", EV " + FormatFixed(100.0 * t.expect_value_m, 1) +
         " cm, \xE2\x88\x9A"
         "Disp " +
         FormatFixed(100.0 * std::sqrt(t.dispersion_m2), 1) + " cm";
}

int MaxCount(const std::vector<int>& histogram) {
  return histogram.empty() ? 0 : *std::max_element(histogram.begin(), histogram.end());
}

}  // namespace

std::string HistogramFigure(const LikelihoodTestResult& before, const LikelihoodTestResult* after,
                            double slot_width_m, const std::string& id) {
  SvgCanvas svg(kWidthPx, kHeightPx, id, "point-to-point distance histogram");
  const std::size_t slots =
      std::max(before.histogram.size(), after ? after->histogram.size() : std::size_t{0});
  const double plot_x0 = kLeftPx, plot_x1 = kWidthPx - kRightPx;
  const double plot_y0 = kTopPx, plot_y1 = kHeightPx - kBottomPx;
  // Legend: one line per stage, with its moments.
  svg.Rect(kLeftPx, 8, 12, 10, style::kBefore);
  svg.Text({kLeftPx + 17, 17}, Moments(after ? "before refinement" : "Likelihood Test", before),
           {11.0});
  if (after) {
    svg.Rect(kLeftPx, 24, 12, 10, style::kAfter, style::kAxis, 0.5);
    svg.Text({kLeftPx + 17, 33}, Moments("after refinement", *after), {11.0});
  }
  svg.Rect(plot_x0, plot_y0, plot_x1 - plot_x0, plot_y1 - plot_y0, "none", style::kFrame, 0.8);
  const int max_count =
      std::max(MaxCount(before.histogram), after ? MaxCount(after->histogram) : 0);
  if (slots == 0 || max_count == 0) {
    svg.Text({0.5 * (plot_x0 + plot_x1), 0.5 * (plot_y0 + plot_y1)},
             "no match pairs: nothing to draw", {12.0, "middle", style::kMessage});
    return svg.Finish();
  }
  const std::vector<double> ticks = NiceTicks(0.0, max_count, 4);
  const LinearAxis y{0.0, std::max<double>(max_count, ticks.back()), plot_y1, plot_y0 + 4};
  const LinearAxis x{0.0, static_cast<double>(slots), plot_x0 + 4, plot_x1 - 4};
  for (const double t : ticks) {
    svg.Line({plot_x0, y(t)}, {plot_x1, y(t)}, style::kGrid, 0.8);
    svg.Text({plot_x0 - 5, y(t) + 4}, FormatFixed(t, 0), {10.0, "end", style::kAxis});
  }
  // Light columns get an outline, so that they stand out in front of the dark ones.
  auto columns = [&](const std::vector<int>& histogram, double width, const char* colour,
                     const char* outline, const char* stage) {
    for (std::size_t k = 0; k < histogram.size(); ++k) {
      if (histogram[k] == 0) continue;
      const double centre = x(k + 0.5), half = 0.5 * width * (x(1) - x(0));
      svg.BeginGroup(std::string(stage) + ", slot " + std::to_string(k) + ": " +
                     std::to_string(histogram[k]) + " pairs");
      svg.Rect(centre - half, y(histogram[k]), 2 * half, y(0) - y(histogram[k]), colour, outline,
               0.5);
      svg.EndGroup();
    }
  };
  columns(before.histogram, after ? kBeforeWidth : kAloneWidth, style::kBefore, "none",
          after ? "before" : "Likelihood Test");
  if (after) columns(after->histogram, kAfterWidth, style::kAfter, style::kAxis, "after");
  // Slot labels: lower bounds in cm every few slots, the last slot as "≥".
  const std::size_t label_step = slots > 12 ? 5 : 1;
  for (std::size_t k = 0; k + 1 < slots; k += label_step)
    svg.Text({x(k), plot_y1 + 14}, FormatFixed(100.0 * slot_width_m * k, 0),
             {10.0, "middle", style::kAxis});
  svg.Text({x(slots - 0.5), plot_y1 + 14},
           "\xE2\x89\xA5" + FormatFixed(100.0 * slot_width_m * (slots - 1), 0),
           {10.0, "middle", style::kAxis});
  svg.Text({0.5 * (plot_x0 + plot_x1), kHeightPx - 8},
           "point-to-point distance [cm], slots of " + FormatFixed(100.0 * slot_width_m, 1) +
               " cm; the last gathers the rest up to T_Map",
           {10.5, "middle", style::kAxis});
  return svg.Finish();
}

std::string HistogramSparkline(const std::vector<int>& histogram, const std::string& id) {
  std::string counts;
  for (const int c : histogram) counts += (counts.empty() ? "" : " ") + std::to_string(c);
  SvgCanvas svg(kSparkWidthPx, kSparkHeightPx, id, "histogram: " + counts);
  svg.Line({0, kSparkHeightPx - 0.5}, {kSparkWidthPx, kSparkHeightPx - 0.5}, style::kFrame, 0.5);
  const int max_count = MaxCount(histogram);
  if (max_count == 0) return svg.Finish();
  const double slot = kSparkWidthPx / histogram.size();
  for (std::size_t k = 0; k < histogram.size(); ++k) {
    if (histogram[k] == 0) continue;
    const double h = (kSparkHeightPx - 2) * histogram[k] / max_count;
    svg.Rect(k * slot + 0.5, kSparkHeightPx - 1 - h, std::max(0.5, slot - 1), h,
             k + 1 == histogram.size() ? style::kInvalid : style::kBefore);
  }
  return svg.Finish();
}

}  // namespace scanloc
