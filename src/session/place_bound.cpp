#include "scanloc/session/place_bound.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <utility>

namespace scanloc {

PlaceBound::PlaceBound(std::vector<MapSignatureSample> samples, double median_expect_value_m,
                       int neighbours)
    : samples_(std::move(samples)),
      median_expect_value_m_(median_expect_value_m),
      neighbours_(neighbours) {
  if (neighbours_ < 1) throw std::invalid_argument("PlaceBound: neighbours must be >= 1");
  if (!std::isfinite(median_expect_value_m_))
    throw std::invalid_argument("PlaceBound: the map's median EV must be finite");
}

double PlaceBound::Excess(const Pose2D& T_world_robot) const {
  if (samples_.empty()) return 0.0;
  std::vector<std::pair<double, double>> near;  // squared distance, EV
  near.reserve(samples_.size());
  for (const MapSignatureSample& s : samples_) {
    const double dx = s.x_m - T_world_robot.x_m, dy = s.y_m - T_world_robot.y_m;
    near.emplace_back(dx * dx + dy * dy, s.expect_value_m);
  }
  const std::size_t k = std::min<std::size_t>(neighbours_, near.size());
  std::partial_sort(near.begin(), near.begin() + k, near.end());
  std::vector<double> values;
  for (std::size_t i = 0; i < k; ++i) values.push_back(near[i].second);
  std::sort(values.begin(), values.end());
  const double median =
      k % 2 ? values[k / 2] : 0.5 * (values[k / 2 - 1] + values[k / 2]);
  return std::max(0.0, median - median_expect_value_m_);
}

}  // namespace scanloc
