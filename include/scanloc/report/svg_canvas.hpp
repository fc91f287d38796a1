#pragma once
// A small SVG writer for the report's figures: shapes in pixel coordinates (y down), every text
// and attribute escaped, coordinates rounded to 0.1 px so that figures with thousands of map
// points stay small.

#include <Eigen/Core>
#include <sstream>
#include <string>
#include <vector>

namespace scanloc {

// A number for an SVG coordinate: rounded to `decimals` (0.1 by default), without trailing zeros.
std::string SvgNumber(double value, int decimals = 1);

struct TextStyle {
  double size_px = 12.0;
  std::string anchor = "start";  // start, middle or end
  std::string colour = "#222";
  bool bold = false;
};

class SvgCanvas {
 public:
  // `id` must be unique in the page: clip paths are named after it. `title` is the figure's
  // accessible name (shown as a tooltip by browsers).
  SvgCanvas(double width_px, double height_px, std::string id, const std::string& title);
  SvgCanvas(const SvgCanvas&) = delete;
  SvgCanvas& operator=(const SvgCanvas&) = delete;

  // Decimals of the coordinates written from now on (default 1, i.e. 0.1 px); figures that the
  // page magnifies need more.
  void set_decimals(int decimals) { decimals_ = decimals; }
  double width() const { return width_px_; }
  double height() const { return height_px_; }

  void Rect(double x, double y, double width, double height, const std::string& fill,
            const std::string& stroke = "none", double stroke_width = 1.0);
  void Line(const Eigen::Vector2d& a, const Eigen::Vector2d& b, const std::string& stroke,
            double width, const std::string& dash = "");
  void Polyline(const std::vector<Eigen::Vector2d>& points, const std::string& stroke,
                double width);
  void Circle(const Eigen::Vector2d& centre, double radius, const std::string& fill,
              const std::string& stroke = "none", double stroke_width = 1.0);
  // Round dots of `diameter_px`, one path for all; points closer than about half a dot to one
  // already drawn add nothing and are dropped.
  void Dots(const std::vector<Eigen::Vector2d>& points, double diameter_px,
            const std::string& colour);
  // An arrow of `length_px` from `tail` along `heading_rad`, measured counter-clockwise from the
  // +x axis as in a map (the canvas's y axis points down, the map's up).
  void Arrow(const Eigen::Vector2d& tail, double heading_rad, double length_px,
             const std::string& colour, double width_px);
  void Text(const Eigen::Vector2d& at, const std::string& text, const TextStyle& style = {});
  // A raster image (e.g. a data: URI) stretched over the rectangle, its pixels drawn as squares
  // when magnified.
  void Image(double x, double y, double width, double height, const std::string& href);

  // Groups nest; each Begin… needs its End. A group's tooltip is shown on hover; `css_class`
  // lets the page style what it holds.
  void BeginGroup(const std::string& tooltip = "", const std::string& css_class = "");
  // A group whose content is clipped to the rectangle.
  void BeginClippedGroup(double x, double y, double width, double height);
  void EndGroup();
  // A link around the content up to EndLink (e.g. "#iteration-12").
  void BeginLink(const std::string& href);
  void EndLink();

  // The finished <svg> element. Throws std::logic_error when a group or link is left open.
  std::string Finish() const;

 private:
  double width_px_, height_px_;
  std::string id_;
  std::ostringstream body_;
  std::vector<char> open_;  // 'g' for each open group, 'a' for each open link
  // Writes </element> for the innermost open element, which must be `element`.
  void Close(char element, const char* caller);
  int clips_ = 0;
  int decimals_ = 1;
  std::string Num(double value) const { return SvgNumber(value, decimals_); }
  std::string Point(const Eigen::Vector2d& p) const { return Num(p.x()) + "," + Num(p.y()); }
};

}  // namespace scanloc
