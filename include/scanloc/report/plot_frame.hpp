#pragma once
// Where a figure's data lands on its canvas: map frames at one scale for x and y (a map is never
// stretched), linear axes for charts, and tick values a person reads at a glance.

#include <Eigen/Core>
#include <limits>
#include <vector>

namespace scanloc {

// An axis-aligned box in world coordinates (metres); empty until a point extends it.
struct Box {
  Eigen::Vector2d min{std::numeric_limits<double>::infinity(),
                      std::numeric_limits<double>::infinity()};
  Eigen::Vector2d max{-std::numeric_limits<double>::infinity(),
                      -std::numeric_limits<double>::infinity()};
  bool empty() const { return !(min.x() <= max.x() && min.y() <= max.y()); }
  void Extend(const Eigen::Vector2d& point);  // non-finite points are ignored
  // Grows by `fraction` of its size on each side, and to at least `min_size_m` on each axis,
  // about its centre. An empty box stays empty.
  Box Padded(double fraction, double min_size_m) const;
};

// The box holding the central (1 − 2·fraction) share of the points along each axis: a few stray
// far returns do not shrink everything else. Empty for no points.
Box CentralBox(const std::vector<Eigen::Vector2d>& points, double fraction);

// World metres to canvas pixels inside a rectangle: the box is fitted whole at one scale and
// centred; y points up in the world and down on the canvas.
class MapFrame {
 public:
  // `world` must not be empty (throws std::invalid_argument).
  MapFrame(const Box& world, double x_px, double y_px, double width_px, double height_px);
  Eigen::Vector2d ToPixel(const Eigen::Vector2d& world) const;
  double pixels_per_m() const { return pixels_per_m_; }
  // True when the pixel lies in the rectangle grown by margin_px.
  bool Inside(const Eigen::Vector2d& pixel, double margin_px = 0.0) const;
  double x() const { return x_px_; }
  double y() const { return y_px_; }
  double width() const { return width_px_; }
  double height() const { return height_px_; }

 private:
  double x_px_, y_px_, width_px_, height_px_;
  double pixels_per_m_;
  Eigen::Vector2d world_centre_;
};

// A value range onto a pixel interval (p0 for v0, p1 for v1; p1 < p0 for a y axis).
struct LinearAxis {
  double v0 = 0.0, v1 = 1.0, p0 = 0.0, p1 = 1.0;
  double operator()(double value) const {
    return v1 == v0 ? p0 : p0 + (value - v0) * (p1 - p0) / (v1 - v0);
  }
};

// About `count` round values (1, 2 or 5 × 10^k apart) covering [low, high].
std::vector<double> NiceTicks(double low, double high, int count);

// The largest 1, 2 or 5 × 10^k not above `limit` (> 0): the length of a scale bar.
double NiceLengthBelow(double limit);

}  // namespace scanloc
