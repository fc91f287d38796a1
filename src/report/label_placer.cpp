#include "scanloc/report/label_placer.hpp"

namespace scanloc {
namespace {

// Average advance of a sans-serif glyph, as a fraction of the font size.
constexpr double kGlyphWidthFraction = 0.58;
// Gap between a label and its anchor, pixels.
constexpr double kGapPx = 4.0;

}  // namespace

double EstimateTextWidth(const std::string& text, double size_px) {
  std::size_t glyphs = 0;
  for (const char c : text)
    if ((static_cast<unsigned char>(c) & 0xC0) != 0x80) ++glyphs;  // not a continuation byte
  return kGlyphWidthFraction * size_px * glyphs;
}

LabelPlacer::LabelPlacer(double x_px, double y_px, double width_px, double height_px, int rings)
    : bounds_{x_px, y_px, x_px + width_px, y_px + height_px}, rings_(rings) {}

void LabelPlacer::Reserve(double x_px, double y_px, double width_px, double height_px) {
  taken_.push_back({x_px, y_px, x_px + width_px, y_px + height_px});
}

bool LabelPlacer::Free(const Rect& r) const {
  if (r.x0 < bounds_.x0 || r.y0 < bounds_.y0 || r.x1 > bounds_.x1 || r.y1 > bounds_.y1)
    return false;
  for (const Rect& t : taken_)
    if (r.x0 < t.x1 && t.x0 < r.x1 && r.y0 < t.y1 && t.y0 < r.y1) return false;
  return true;
}

std::optional<Eigen::Vector2d> LabelPlacer::Place(const Eigen::Vector2d& anchor,
                                                  const std::string& text, double size_px) {
  const double width = EstimateTextWidth(text, size_px);
  const double height = size_px;
  for (int ring = 0; ring < rings_; ++ring) {
    const double gap = kGapPx + ring * height;
    // Right, left, above, below, then the four diagonals; (x, y) is the box's top-left.
    const Eigen::Vector2d corners[] = {
        {anchor.x() + gap, anchor.y() - height / 2},
        {anchor.x() - gap - width, anchor.y() - height / 2},
        {anchor.x() - width / 2, anchor.y() - gap - height},
        {anchor.x() - width / 2, anchor.y() + gap},
        {anchor.x() + gap, anchor.y() - gap - height},
        {anchor.x() + gap, anchor.y() + gap},
        {anchor.x() - gap - width, anchor.y() - gap - height},
        {anchor.x() - gap - width, anchor.y() + gap},
    };
    for (const Eigen::Vector2d& c : corners) {
      const Rect r{c.x(), c.y(), c.x() + width, c.y() + height};
      if (!Free(r)) continue;
      taken_.push_back(r);
      return Eigen::Vector2d(c.x(), c.y() + 0.8 * height);  // baseline
    }
  }
  return std::nullopt;
}

}  // namespace scanloc
