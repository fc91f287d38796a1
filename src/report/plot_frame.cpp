#include "scanloc/report/plot_frame.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace scanloc {

void Box::Extend(const Eigen::Vector2d& point) {
  if (!point.allFinite()) return;
  min = min.cwiseMin(point);
  max = max.cwiseMax(point);
}

Box Box::Padded(double fraction, double min_size_m) const {
  if (empty()) return *this;
  const Eigen::Vector2d centre = 0.5 * (min + max);
  Eigen::Vector2d half = 0.5 * (max - min) * (1.0 + 2.0 * fraction);
  half = half.cwiseMax(Eigen::Vector2d::Constant(0.5 * min_size_m));
  Box out;
  out.min = centre - half;
  out.max = centre + half;
  return out;
}

Box CentralBox(const std::vector<Eigen::Vector2d>& points, double fraction) {
  Box box;
  std::vector<double> xs, ys;
  xs.reserve(points.size());
  ys.reserve(points.size());
  for (const auto& p : points)
    if (p.allFinite()) {
      xs.push_back(p.x());
      ys.push_back(p.y());
    }
  if (xs.empty()) return box;
  const std::size_t lo = static_cast<std::size_t>(std::clamp(fraction, 0.0, 0.5) * (xs.size() - 1));
  const std::size_t hi = xs.size() - 1 - lo;
  auto nth = [](std::vector<double>& values, std::size_t k) {
    std::nth_element(values.begin(), values.begin() + k, values.end());
    return values[k];
  };
  box.Extend({nth(xs, lo), nth(ys, lo)});
  box.Extend({nth(xs, hi), nth(ys, hi)});
  return box;
}

MapFrame::MapFrame(const Box& world, double x_px, double y_px, double width_px, double height_px)
    : x_px_(x_px), y_px_(y_px), width_px_(width_px), height_px_(height_px) {
  if (world.empty()) throw std::invalid_argument("MapFrame: the world box is empty");
  const Eigen::Vector2d size = (world.max - world.min).cwiseMax(Eigen::Vector2d::Constant(1e-9));
  pixels_per_m_ = std::min(width_px / size.x(), height_px / size.y());
  world_centre_ = 0.5 * (world.min + world.max);
}

Eigen::Vector2d MapFrame::ToPixel(const Eigen::Vector2d& world) const {
  const Eigen::Vector2d offset = (world - world_centre_) * pixels_per_m_;
  return {x_px_ + 0.5 * width_px_ + offset.x(), y_px_ + 0.5 * height_px_ - offset.y()};
}

bool MapFrame::Inside(const Eigen::Vector2d& pixel, double margin_px) const {
  return pixel.x() >= x_px_ - margin_px && pixel.x() <= x_px_ + width_px_ + margin_px &&
         pixel.y() >= y_px_ - margin_px && pixel.y() <= y_px_ + height_px_ + margin_px;
}

std::vector<double> NiceTicks(double low, double high, int count) {
  if (!std::isfinite(low) || !std::isfinite(high) || count < 1) return {};
  if (high < low) std::swap(low, high);
  if (high == low) return {low};
  const double step = NiceLengthBelow((high - low) / count * 1.5);
  // Tick k is k·mantissa·10^exponent, computed so that 0.6 comes out as 0.6, not
  // 0.6000000000000001.
  const int exponent = static_cast<int>(std::floor(std::log10(step) + 1e-9));
  const double mantissa = std::round(step / std::pow(10.0, exponent));
  auto tick = [&](long long k) {
    const double m = static_cast<double>(k) * mantissa;
    return exponent >= 0 ? m * std::pow(10.0, exponent) : m / std::pow(10.0, -exponent);
  };
  std::vector<double> ticks;
  for (long long k = static_cast<long long>(std::ceil(low / step - 1e-9));
       tick(k) <= high + 1e-9 * step; ++k)
    ticks.push_back(tick(k) == 0.0 ? 0.0 : tick(k));
  return ticks;
}

double NiceLengthBelow(double limit) {
  if (!(limit > 0.0) || !std::isfinite(limit))
    throw std::invalid_argument("NiceLengthBelow: the limit must be positive and finite");
  const double decade = std::pow(10.0, std::floor(std::log10(limit)));
  for (const double factor : {5.0, 2.0, 1.0})
    if (factor * decade <= limit * (1.0 + 1e-12)) return factor * decade;
  return decade;
}

}  // namespace scanloc
