#pragma once
// A figure's furniture: the legend (symbols with their meanings in rows below the plot) and the
// scale bar of a map.

#include <string>
#include <vector>

#include "scanloc/report/label_placer.hpp"
#include "scanloc/report/plot_frame.hpp"
#include "scanloc/report/svg_canvas.hpp"

namespace scanloc {

struct LegendItem {
  enum class Symbol { kDot, kLine, kDashedLine, kArrow, kRing };
  Symbol symbol = Symbol::kDot;
  std::string colour;
  std::string text;
};

// Draws the items left to right from (x, y) (the first line's vertical centre), wrapping at
// x + width; returns the height used.
double DrawLegend(SvgCanvas& svg, const std::vector<LegendItem>& items, double x_px, double y_px,
                  double width_px);

// The height DrawLegend would use.
double LegendHeight(const std::vector<LegendItem>& items, double width_px);

// A scale bar of a round length (about a fifth of the frame's width) in the frame's lower left
// corner; its area is kept free of labels when `labels` is given.
void DrawScaleBar(SvgCanvas& svg, const MapFrame& frame, LabelPlacer* labels = nullptr);

}  // namespace scanloc
