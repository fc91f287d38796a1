#include "scanloc/graph/odometry_model.hpp"

#include "scanloc/graph/variance_components.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <functional>
#include <stdexcept>

namespace scanloc {
namespace {

// Medians of χ² with 1, 2 and 3 degrees of freedom.
constexpr double kChi2Median1 = 0.454936;
constexpr double kChi2Median2 = 1.386294;
constexpr double kChi2Median3 = 2.365974;

double Median(std::vector<double> values) {
  const std::size_t half = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + half, values.end());
  if (values.size() % 2 == 1) return values[half];
  const double upper = values[half];
  return 0.5 * (upper + *std::max_element(values.begin(), values.begin() + half));
}

// The scale λ ≥ 0 at which the median of the whitened squared misses, `whitened(λ)` (falling as λ
// grows), meets `target`: 0 when it is below it already at 0, bisected in log space otherwise.
double FitScale(const std::function<double(double)>& whitened, double target) {
  double low = 1e-15, high = 1e3;
  if (whitened(0.0) <= target) return 0.0;
  if (whitened(high) >= target) return high;
  for (int i = 0; i < 80; ++i) {
    const double middle = std::sqrt(low * high);
    (whitened(middle) > target ? low : high) = middle;
  }
  return std::sqrt(low * high);
}

}  // namespace

void OdometryModelOptions::Validate() const {
  if (!(turn_weight_m_per_rad >= 0.0 && floor_m > 0.0 && floor_rad > 0.0 && stretch_m > 0.0 &&
        position_per_heading_m2 >= 0.0) ||
      !std::isfinite(turn_weight_m_per_rad + floor_m + floor_rad + stretch_m +
                     position_per_heading_m2))
    throw std::invalid_argument(
        "OdometryModelOptions: turn_weight_m_per_rad and position_per_heading_m2 must be >= 0, "
        "the floors and stretch_m positive");
}

OdometryModel::OdometryModel(const OdometryModelOptions& options) : options_(options) {
  options_.Validate();
}

OdometryStepShape OdometryModel::Shape(const Pose2D& increment) const {
  const double d = std::hypot(increment.x_m, increment.y_m);
  const double turn = std::abs(NormalizeAngle(increment.yaw_rad));
  OdometryStepShape shape;
  shape.position = Eigen::Vector3d(d, d, 0.0).asDiagonal();
  shape.heading = Eigen::Vector3d(0.0, 0.0, d + options_.turn_weight_m_per_rad * turn).asDiagonal();
  const double fm = options_.floor_m * options_.floor_m,
               fr = options_.floor_rad * options_.floor_rad;
  shape.floor = Eigen::Vector3d(fm, fm, fr).asDiagonal();
  return shape;
}

void OdometryModel::Learn(std::vector<ChainMisses> closures, std::vector<ChainMisses> stretches) {
  misses_ = std::move(closures);
  stretches_ = std::move(stretches);
  Fit();
}

// λ_r from three sources compared two by two in heading (variance_components.hpp): each
// closure against the odometry chain (λ_r and the closure's own error, a variance λ_c alike for
// every closure) and against the matched chain (λ_s and λ_c), each stretch the odometry chain
// against the matched one (λ_r and λ_s). A perfect odometry's closures miss by their own error,
// which no longer passes for the odometry's.
double HeadingScale(const std::vector<ChainMisses>& closures,
                    const std::vector<ChainMisses>& stretches) {
  std::vector<VarianceObservation> observations;
  for (const ChainMisses& m : closures) {
    observations.push_back({m.odometry_miss(2) * m.odometry_miss(2), m.odometry_floor(2, 2),
                            Eigen::Vector3d(m.odometry_per_heading(2, 2), 0.0, 1.0)});
    observations.push_back({m.matched_miss(2) * m.matched_miss(2), 0.0,
                            Eigen::Vector3d(0.0, m.matched_covariance(2, 2), 1.0)});
  }
  for (const ChainMisses& m : stretches)
    observations.push_back(
        {m.odometry_miss(2) * m.odometry_miss(2), m.odometry_floor(2, 2),
         Eigen::Vector3d(m.odometry_per_heading(2, 2), m.matched_covariance(2, 2), 0.0)});
  const Eigen::VectorXd x = FitVarianceComponents(observations);
  return x(0);
}

// λ_t fitted on the position misses of the stretches, the heading's part at λ_r and the matched
// chain's at λ_s counted in.
double PositionScale(const std::vector<ChainMisses>& stretches, double heading_scale,
                     double matched_scale) {
  std::vector<double> values(stretches.size());
  return FitScale(
      [&](double lambda) {
        for (std::size_t i = 0; i < stretches.size(); ++i) {
          const ChainMisses& m = stretches[i];
          const Eigen::Matrix2d covariance =
              (lambda * m.odometry_per_position + heading_scale * m.odometry_per_heading +
               m.odometry_floor + matched_scale * m.matched_covariance)
                  .topLeftCorner<2, 2>();
          const Eigen::Vector2d miss = m.odometry_miss.head<2>();
          values[i] = miss.dot(covariance.inverse() * miss);
        }
        return Median(values);
      },
      kChi2Median2);
}

// The matched chain's scale on its closures' misses, the heading's from the three sources, the
// position's from the stretches, and at least what a differential drive with that heading noise
// has (where the stretches cannot tell it from the heading's).
void OdometryModel::Fit() {
  std::vector<double> values(misses_.size());
  for (std::size_t i = 0; i < misses_.size(); ++i) {
    const ChainMisses& m = misses_[i];
    values[i] = m.matched_miss.dot(m.matched_covariance.inverse() * m.matched_miss);
  }
  matched_ = std::clamp(Median(values) / kChi2Median3, 1e-3, 1e6);
  heading_ = HeadingScale(misses_, stretches_);
  position_ = stretches_.empty() ? 0.0 : PositionScale(stretches_, heading_, matched_);
  position_ = std::max(position_, options_.position_per_heading_m2 * heading_);
}

Eigen::Matrix3d OdometryModel::StepCovariance(const Pose2D& increment) const {
  const OdometryStepShape shape = Shape(increment);
  return (position_ * shape.position + heading_ * shape.heading + shape.floor) / matched_;
}

}  // namespace scanloc
