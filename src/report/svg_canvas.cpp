#include "scanloc/report/svg_canvas.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <unordered_set>

#include "scanloc/report/markup.hpp"

namespace scanloc {
namespace {

// The arrow head's length and half width as fractions of the arrow's length (with a floor, so
// that short arrows keep a visible head).
constexpr double kHeadLengthFraction = 0.32;
constexpr double kMinHeadLengthPx = 6.0, kMaxHeadLengthPx = 12.0;
constexpr double kHeadHalfWidthFraction = 0.45;

std::string Attribute(const std::string& name, const std::string& value) {
  return " " + name + "=\"" + EscapeMarkup(value) + "\"";
}

}  // namespace

std::string SvgNumber(double value, int decimals) {
  if (!std::isfinite(value)) return "0";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, "%.*f", std::clamp(decimals, 0, 9), value);
  std::string text = buffer;
  if (text.find('.') != std::string::npos) {
    while (text.back() == '0') text.pop_back();
    if (text.back() == '.') text.pop_back();
  }
  if (text == "-0") text = "0";
  return text;
}

SvgCanvas::SvgCanvas(double width_px, double height_px, std::string id, const std::string& title)
    : width_px_(width_px), height_px_(height_px), id_(std::move(id)) {
  if (!(width_px > 0.0) || !(height_px > 0.0))
    throw std::invalid_argument("SvgCanvas: width and height must be positive");
  body_ << "<title>" << EscapeMarkup(title) << "</title>\n";
}

void SvgCanvas::Rect(double x, double y, double width, double height, const std::string& fill,
                     const std::string& stroke, double stroke_width) {
  body_ << "<rect x=\"" << Num(x) << "\" y=\"" << Num(y) << "\" width=\"" << Num(width)
        << "\" height=\"" << Num(height) << "\"" << Attribute("fill", fill)
        << Attribute("stroke", stroke);
  if (stroke != "none") body_ << " stroke-width=\"" << Num(stroke_width) << "\"";
  body_ << "/>\n";
}

void SvgCanvas::Line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const std::string& stroke,
                     double width, const std::string& dash) {
  body_ << "<line x1=\"" << Num(a.x()) << "\" y1=\"" << Num(a.y()) << "\" x2=\"" << Num(b.x())
        << "\" y2=\"" << Num(b.y()) << "\"" << Attribute("stroke", stroke) << " stroke-width=\""
        << Num(width) << "\"";
  if (!dash.empty()) body_ << Attribute("stroke-dasharray", dash);
  body_ << "/>\n";
}

void SvgCanvas::Polyline(const std::vector<Eigen::Vector2d>& points, const std::string& stroke,
                         double width) {
  if (points.size() < 2) return;
  body_ << "<polyline fill=\"none\"" << Attribute("stroke", stroke) << " stroke-width=\""
        << Num(width) << "\" stroke-linejoin=\"round\" points=\"";
  std::string previous;
  for (const Eigen::Vector2d& p : points) {
    std::string text = Point(p);
    if (text == previous) continue;  // a robot standing still adds nothing to the line
    body_ << text << ' ';
    previous = std::move(text);
  }
  body_ << "\"/>\n";
}

void SvgCanvas::Circle(const Eigen::Vector2d& centre, double radius, const std::string& fill,
                       const std::string& stroke, double stroke_width) {
  body_ << "<circle cx=\"" << Num(centre.x()) << "\" cy=\"" << Num(centre.y()) << "\" r=\""
        << Num(radius) << "\"" << Attribute("fill", fill) << Attribute("stroke", stroke);
  if (stroke != "none") body_ << " stroke-width=\"" << Num(stroke_width) << "\"";
  body_ << "/>\n";
}

void SvgCanvas::Dots(const std::vector<Eigen::Vector2d>& points, double diameter_px,
                     const std::string& colour) {
  // Zero-length subpaths with round caps draw as dots: about 12 bytes a point.
  const double cell_px = std::max(0.5, 0.5 * diameter_px);
  std::unordered_set<long long> taken;
  std::ostringstream path;
  for (const Eigen::Vector2d& p : points) {
    if (!p.allFinite()) continue;
    const long long cx = std::llround(p.x() / cell_px), cy = std::llround(p.y() / cell_px);
    // Unsigned shift: the bits of cx << 32 without shifting a negative number.
    const auto key = static_cast<long long>((static_cast<unsigned long long>(cx) << 32) ^
                                            (static_cast<unsigned long long>(cy) & 0xffffffffULL));
    if (!taken.insert(key).second) continue;
    path << 'M' << Num(cx * cell_px) << ' ' << Num(cy * cell_px) << "h0";
  }
  if (taken.empty()) return;
  body_ << "<path fill=\"none\"" << Attribute("stroke", colour) << " stroke-width=\""
        << Num(diameter_px) << "\" stroke-linecap=\"round\" d=\"" << path.str() << "\"/>\n";
}

void SvgCanvas::Arrow(const Eigen::Vector2d& tail, double heading_rad, double length_px,
                      const std::string& colour, double width_px) {
  const Eigen::Vector2d direction(std::cos(heading_rad), -std::sin(heading_rad));  // y down
  const Eigen::Vector2d normal(-direction.y(), direction.x());
  const Eigen::Vector2d tip = tail + length_px * direction;
  const double head_length =
      std::clamp(kHeadLengthFraction * length_px, kMinHeadLengthPx, kMaxHeadLengthPx);
  const Eigen::Vector2d base = tip - head_length * direction;
  const double half_width = kHeadHalfWidthFraction * head_length;
  Line(tail, base, colour, width_px);
  body_ << "<polygon points=\"" << Point(tip) << ' ' << Point(base + half_width * normal) << ' '
        << Point(base - half_width * normal) << "\"" << Attribute("fill", colour) << "/>\n";
}

void SvgCanvas::Text(const Eigen::Vector2d& at, const std::string& text, const TextStyle& style) {
  body_ << "<text x=\"" << Num(at.x()) << "\" y=\"" << Num(at.y()) << "\" font-size=\""
        << Num(style.size_px) << "\"" << Attribute("text-anchor", style.anchor)
        << Attribute("fill", style.colour);
  if (style.bold) body_ << " font-weight=\"bold\"";
  body_ << ">" << EscapeMarkup(text) << "</text>\n";
}

void SvgCanvas::Image(double x, double y, double width, double height, const std::string& href) {
  body_ << "<image x=\"" << Num(x) << "\" y=\"" << Num(y) << "\" width=\"" << Num(width)
        << "\" height=\"" << Num(height)
        << "\" preserveAspectRatio=\"none\" style=\"image-rendering:pixelated\""
        << Attribute("href", href) << "/>\n";
}

void SvgCanvas::BeginGroup(const std::string& tooltip, const std::string& css_class) {
  body_ << "<g" << (css_class.empty() ? "" : Attribute("class", css_class)) << ">";
  if (!tooltip.empty()) body_ << "<title>" << EscapeMarkup(tooltip) << "</title>";
  body_ << '\n';
  open_.push_back('g');
}

void SvgCanvas::BeginClippedGroup(double x, double y, double width, double height) {
  const std::string clip_id = id_ + "-clip" + std::to_string(clips_++);
  body_ << "<clipPath" << Attribute("id", clip_id) << "><rect x=\"" << Num(x) << "\" y=\"" << Num(y)
        << "\" width=\"" << Num(width) << "\" height=\"" << Num(height) << "\"/></clipPath>\n<g"
        << Attribute("clip-path", "url(#" + clip_id + ")") << ">\n";
  open_.push_back('g');
}

void SvgCanvas::Close(char element, const char* caller) {
  if (open_.empty() || open_.back() != element)
    throw std::logic_error(std::string("SvgCanvas::") + caller + " without its opening element");
  body_ << "</" << element << ">\n";
  open_.pop_back();
}

void SvgCanvas::EndGroup() {
  Close('g', "EndGroup");
}

void SvgCanvas::BeginLink(const std::string& href) {
  body_ << "<a" << Attribute("href", href) << ">\n";
  open_.push_back('a');
}

void SvgCanvas::EndLink() {
  Close('a', "EndLink");
}

std::string SvgCanvas::Finish() const {
  if (!open_.empty()) throw std::logic_error("SvgCanvas::Finish: a group or link is open");
  std::ostringstream svg;
  svg << "<svg xmlns=\"http://www.w3.org/2000/svg\"" << Attribute("id", id_) << " width=\""
      << Num(width_px_) << "\" height=\"" << Num(height_px_) << "\" viewBox=\"0 0 "
      << Num(width_px_) << ' ' << Num(height_px_) << "\" font-family=\"sans-serif\" role=\"img\">\n"
      << body_.str() << "</svg>\n";
  return svg.str();
}

}  // namespace scanloc
