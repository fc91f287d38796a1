#include "scanloc/report/legend.hpp"

#include "scanloc/report/figure_style.hpp"
#include "scanloc/report/markup.hpp"

namespace scanloc {
namespace {

constexpr double kFontPx = 11.0;
constexpr double kLinePx = 17.0;
constexpr double kSymbolPx = 18.0;  // room for the symbol before its text
constexpr double kGapPx = 14.0;     // between items
constexpr double kScaleBarFraction = 0.2;

double ItemWidth(const LegendItem& item) {
  return kSymbolPx + 4.0 + EstimateTextWidth(item.text, kFontPx) + kGapPx;
}

// Calls draw(item, x, y) for each item at its place; returns the height used.
template <class Draw>
double Layout(const std::vector<LegendItem>& items, double x_px, double y_px, double width_px,
              Draw draw) {
  if (items.empty()) return 0.0;
  double x = x_px, y = y_px;
  for (const LegendItem& item : items) {
    const double w = ItemWidth(item);
    if (x > x_px && x + w > x_px + width_px) {
      x = x_px;
      y += kLinePx;
    }
    draw(item, x, y);
    x += w;
  }
  return y - y_px + kLinePx;
}

}  // namespace

double DrawLegend(SvgCanvas& svg, const std::vector<LegendItem>& items, double x_px, double y_px,
                  double width_px) {
  return Layout(items, x_px, y_px, width_px, [&](const LegendItem& item, double x, double y) {
    using Symbol = LegendItem::Symbol;
    switch (item.symbol) {
      case Symbol::kDot:
        svg.Circle({x + 9, y}, 2.5, item.colour);
        break;
      case Symbol::kLine:
        svg.Line({x + 1, y}, {x + 17, y}, item.colour, 2.0);
        break;
      case Symbol::kDashedLine:
        svg.Line({x + 1, y}, {x + 17, y}, item.colour, 1.5, "4 3");
        break;
      case Symbol::kArrow:
        svg.Arrow({x + 1, y}, 0.0, 17, item.colour, 1.8);
        break;
      case Symbol::kRing:
        svg.Circle({x + 9, y}, 4.0, "none", item.colour, 1.5);
        break;
    }
    svg.Text({x + kSymbolPx + 4, y + 4}, item.text, {kFontPx, "start", "#333"});
  });
}

void DrawScaleBar(SvgCanvas& svg, const MapFrame& frame, LabelPlacer* labels) {
  const double length_m = NiceLengthBelow(kScaleBarFraction * frame.width() / frame.pixels_per_m());
  const double length_px = length_m * frame.pixels_per_m();
  const double x = frame.x() + 14, y = frame.y() + frame.height() - 14;
  svg.Rect(x - 6, y - 18, length_px + 12, 26, "white");
  svg.Line({x, y}, {x + length_px, y}, "#222", 2.0);
  svg.Line({x, y - 4}, {x, y + 4}, "#222", 1.5);
  svg.Line({x + length_px, y - 4}, {x + length_px, y + 4}, "#222", 1.5);
  const std::string text =
      length_m >= 1.0 ? FormatFixed(length_m, 0) + " m" : FormatFixed(100.0 * length_m, 0) + " cm";
  svg.Text({x + 0.5 * length_px, y - 6}, text, {kFontPx, "middle", "#222"});
  if (labels) labels->Reserve(x - 6, y - 18, length_px + 12, 26);
}

double LegendHeight(const std::vector<LegendItem>& items, double width_px) {
  return Layout(items, 0.0, 0.0, width_px, [](const LegendItem&, double, double) {});
}

void DrawIterationAxis(SvgCanvas& svg, const LinearAxis& x, double last_index, double axis_y,
                       double x0_px, double x1_px) {
  for (const double t : NiceTicks(0.0, last_index, 8))
    svg.Text({x(t), axis_y + 14}, FormatFixed(t, 0), {10.0, "middle", figure_style::kAxis});
  svg.Text({0.5 * (x0_px + x1_px), axis_y + 28}, "iteration",
           {10.5, "middle", figure_style::kAxis});
}

SvgCanvas TwoPanelCanvas(const TwoPanelLayout& layout, const std::vector<LegendItem>& legend,
                         const std::string& id, const std::string& title) {
  const double legend_px = LegendHeight(legend, layout.x1() - layout.x0());
  return SvgCanvas(layout.width_px, layout.Height(legend_px), id, title);
}

void DrawLegendBelow(SvgCanvas& svg, const TwoPanelLayout& layout,
                     const std::vector<LegendItem>& legend) {
  const double width = layout.x1() - layout.x0();
  DrawLegend(svg, legend, layout.x0(), svg.height() - LegendHeight(legend, width), width);
}

std::string FinishEmpty(SvgCanvas& svg, const TwoPanelLayout& layout, const std::string& message) {
  const double top = layout.top_px, height = layout.AxisY() - top;
  svg.Rect(layout.x0(), top, layout.x1() - layout.x0(), height, "none", figure_style::kFrame, 0.8);
  svg.Text({0.5 * (layout.x0() + layout.x1()), top + 0.5 * height}, message,
           {13.0, "middle", figure_style::kMessage});
  return svg.Finish();
}

}  // namespace scanloc
