#include "point_line_fit.hpp"

#include <algorithm>
#include <cmath>

#include "scanloc/maps/point_map.hpp"

namespace scanloc {
namespace {

using Neighbours = std::vector<std::pair<std::uint32_t, double>>;

bool Nearer(const std::pair<std::uint32_t, double>& a, const std::pair<std::uint32_t, double>& b) {
  return a.second < b.second || (a.second == b.second && a.first < b.first);
}

// Keeps the k nearest (index, squared distance) offered, nearest first, ties by index: the
// order then does not depend on the order they are offered in, nor do the fit's sums. Insertion
// into a short sorted list: k is a handful, and most offers are farther than the k-th.
void OfferNearest(Neighbours& nearest, std::size_t k, std::uint32_t index,
                  double squared_distance) {
  const std::pair<std::uint32_t, double> item{index, squared_distance};
  if (nearest.size() == k && !Nearer(item, nearest.back())) return;
  if (nearest.size() < k) nearest.push_back(item);
  std::size_t i = nearest.size() - 1;
  for (; i > 0 && Nearer(item, nearest[i - 1]); --i) nearest[i] = nearest[i - 1];
  nearest[i] = item;
}

// The line through the points, in the given order (the sums depend on it, to the last bit).
bool FitLine(const PointMap& points, const Neighbours& nearest, double max_thickness,
             SurfaceLine& line) {
  Eigen::Vector2d centroid = Eigen::Vector2d::Zero();
  for (const auto& [index, squared_distance] : nearest) centroid += points.point(index);
  centroid /= static_cast<double>(nearest.size());
  Eigen::Matrix2d spread = Eigen::Matrix2d::Zero();
  for (const auto& [index, squared_distance] : nearest) {
    const Eigen::Vector2d d = points.point(index) - centroid;
    spread += d * d.transpose();
  }
  const SpreadAxes axes = SymmetricEigen2(spread(0, 0), spread(0, 1), spread(1, 1));
  if (!(axes.largest > 0.0)) return false;
  if (std::sqrt(std::max(0.0, axes.smallest) / axes.largest) > max_thickness) return false;
  line.normal = axes.minor_axis;
  line.offset = line.normal.dot(centroid);
  return true;
}

}  // namespace

SpreadAxes SymmetricEigen2(double a, double b, double c) {
  SpreadAxes axes;
  const double mean = 0.5 * (a + c), half_gap = std::hypot(0.5 * (a - c), b);
  axes.largest = mean + half_gap;
  axes.smallest = mean - half_gap;
  // (M − λ·I)·v = 0 by either row; the longer of the two solutions is the better conditioned.
  const Eigen::Vector2d by_first(b, axes.smallest - a), by_second(axes.smallest - c, b);
  const Eigen::Vector2d& v =
      by_first.squaredNorm() >= by_second.squaredNorm() ? by_first : by_second;
  const double length = v.norm();
  // A multiple of the identity (a circle of points, or one point): every direction is an axis.
  axes.minor_axis = length > 0.0 ? Eigen::Vector2d(v / length) : Eigen::Vector2d(1.0, 0.0);
  return axes;
}

bool FitPointLine(const PointMap& points, const Eigen::Vector2d& query,
                  const PointLineFitOptions& options, SurfaceLine& line) {
  thread_local Neighbours found, nearest;  // reused: no allocation
  points.RadiusSearch(query, options.radius_m, found);
  nearest.clear();
  const auto k = static_cast<std::size_t>(options.neighbours);
  for (const auto& [index, squared_distance] : found)
    OfferNearest(nearest, k, index, squared_distance);
  if (nearest.size() < 2) return false;
  return FitLine(points, nearest, options.max_thickness, line);
}

void BeamLineFits::Reset() {
  has_pool_ = false;
  has_fit_ = false;
}

bool BeamLineFits::Fit(const PointMap& points, const Eigen::Vector2d& query,
                       const PointLineFitOptions& options, SurfaceLine& line) {
  // The pool's radius has a hair of slack over the margin, so that rounding in the distances
  // cannot drop a point the triangle inequality promises.
  if (!has_pool_ || (query - pool_centre_).norm() > kPoolMarginM) {
    thread_local Neighbours found;
    points.RadiusSearch(query, options.radius_m + kPoolMarginM + 1e-6, found);
    // Sorted before the points' coordinates join them: half the bytes to move.
    std::sort(found.begin(), found.end(),
              [](const auto& a, const auto& b) { return a.second < b.second; });
    pool_.clear();
    for (const auto& [index, squared_distance] : found)
      pool_.push_back({index, points.point(index), squared_distance});
    pool_centre_ = query;
    has_pool_ = true;
  }
  // A member, not thread_local: in a shared library every access to one is a call.
  Neighbours& nearest = nearest_;
  nearest.clear();
  const auto k = static_cast<std::size_t>(options.neighbours);
  const double radius2 = options.radius_m * options.radius_m;
  // Pooled points come nearest the pool's centre first. A point is at least its distance from
  // the centre less the query's, so once that passes the k-th nearest found (or the radius), no
  // later one can enter: the same k as a pass over the whole pool. Compared squared, as
  // (reach + shift)² against the squared distance from the centre; the micrometre of slack
  // keeps rounding from cutting a tie.
  const double shift = (query - pool_centre_).norm() + 1e-6;
  double limit2 = (options.radius_m + shift) * (options.radius_m + shift);
  for (const PoolPoint& pooled : pool_) {
    if (pooled.squared_distance > limit2) break;
    const double d2 = (pooled.point - query).squaredNorm();  // as PointMap::RadiusSearch
    if (!(d2 < radius2)) continue;
    OfferNearest(nearest, k, pooled.index, d2);
    if (nearest.size() == k) {
      const double reach = std::sqrt(nearest.back().second) + shift;
      limit2 = reach * reach;
    }
  }
  if (nearest.size() < 2) return false;
  const bool same = has_fit_ && fitted_.size() == nearest.size() &&
                    std::equal(nearest.begin(), nearest.end(), fitted_.begin(),
                               [](const auto& a, std::uint32_t b) { return a.first == b; });
  if (!same) {
    fitted_.clear();
    for (const auto& [index, squared_distance] : nearest) fitted_.push_back(index);
    fitted_ok_ = FitLine(points, nearest, options.max_thickness, fitted_line_);
    has_fit_ = true;
  }
  if (fitted_ok_) line = fitted_line_;
  return fitted_ok_;
}

}  // namespace scanloc
