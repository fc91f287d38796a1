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

// The iteration axis under a series plot: about eight round ticks of `x` from 0 to last_index at
// axis_y, and its title centred between x0_px and x1_px.
void DrawIterationAxis(SvgCanvas& svg, const LinearAxis& x, double last_index, double axis_y,
                       double x0_px, double x1_px);

// Two panels stacked over the iterations and the legend below them: the series figures' layout.
struct TwoPanelLayout {
  double width_px = 820.0, panel_height_px = 150.0, gap_px = 26.0;
  double left_px = 56.0, right_px = 14.0, top_px = 12.0, bottom_px = 40.0;
  double x0() const { return left_px; }
  double x1() const { return width_px - right_px; }
  double PanelTop(int panel) const { return top_px + panel * (panel_height_px + gap_px); }
  double AxisY() const { return PanelTop(2) - gap_px; }  // under the second panel
  double Height(double legend_px) const { return AxisY() + bottom_px + 8 + legend_px; }
};

// A canvas of `layout` with room for `legend` below the panels.
SvgCanvas TwoPanelCanvas(const TwoPanelLayout& layout, const std::vector<LegendItem>& legend,
                         const std::string& id, const std::string& title);
// `legend` drawn in the room TwoPanelCanvas left for it.
void DrawLegendBelow(SvgCanvas& svg, const TwoPanelLayout& layout,
                     const std::vector<LegendItem>& legend);

// Both panels' frame with `message` in the middle, where there is nothing to draw; returns the
// finished figure.
std::string FinishEmpty(SvgCanvas& svg, const TwoPanelLayout& layout, const std::string& message);

}  // namespace scanloc
