#pragma once
// Places short labels beside their anchors without letting them overlap each other: candidate
// postures of one iteration often share a position and differ only in heading.

#include <Eigen/Core>
#include <optional>
#include <string>
#include <vector>

namespace scanloc {

class LabelPlacer {
 public:
  // Labels must stay inside the rectangle [x, x + width] × [y, y + height] (pixels). `rings`
  // rings of positions are tried around an anchor, each a line further out: 1 keeps every label
  // beside its anchor and leaves out those that find no room there.
  LabelPlacer(double x_px, double y_px, double width_px, double height_px, int rings = 4);
  // The baseline start of a label of `text` at `size_px`, beside `anchor`: the first of a few
  // positions around it (then further away) that overlaps no label placed so far; nullopt when
  // none is free, and the label is best left out.
  std::optional<Eigen::Vector2d> Place(const Eigen::Vector2d& anchor, const std::string& text,
                                       double size_px);
  // Keeps labels off an area (e.g. a legend or scale bar).
  void Reserve(double x_px, double y_px, double width_px, double height_px);

 private:
  struct Rect {
    double x0, y0, x1, y1;
  };
  bool Free(const Rect& r) const;
  Rect bounds_;
  int rings_;
  std::vector<Rect> taken_;
};

// The approximate width of `text` in a sans-serif font of size_px (UTF-8 aware).
double EstimateTextWidth(const std::string& text, double size_px);

}  // namespace scanloc
