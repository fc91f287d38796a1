#include "scanloc/graph/odometry_model.hpp"

#include "scanloc/graph/variance_components.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace scanloc {
namespace {

// The median of χ² with 3 degrees of freedom.
constexpr double kChi2Median3 = 2.365974;
// A scale the misses know only roughly is taken this many standard deviations above its fit.
constexpr double kBoundSigmas = 2.0;

double Median(std::vector<double> values) {
  const std::size_t half = values.size() / 2;
  std::nth_element(values.begin(), values.begin() + half, values.end());
  if (values.size() % 2 == 1) return values[half];
  const double upper = values[half];
  return 0.5 * (upper + *std::max_element(values.begin(), values.begin() + half));
}

}  // namespace

void OdometryModelOptions::Validate() const {
  if (!(turn_weight_m_per_rad >= 0.0 && floor_m > 0.0 && floor_rad > 0.0 && stretch_m > 0.0 &&
        position_per_heading_m2 >= 0.0 && heading_test_chi2 >= 0.0) ||
      !std::isfinite(turn_weight_m_per_rad + floor_m + floor_rad + stretch_m +
                     position_per_heading_m2 + heading_test_chi2))
    throw std::invalid_argument(
        "OdometryModelOptions: turn_weight_m_per_rad, position_per_heading_m2 and "
        "heading_test_chi2 must be >= 0, the floors and stretch_m positive");
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
// which no longer passes for the odometry's. (A matched scan's jitter in heading, a mrad, is
// small beside what the chains turn apart over a stretch: a component of its own for it was
// measured and not kept.) λ_r is zero unless the misses reject zero: twice the log-likelihood of
// this fit, against a fit without λ_r where each closure errs only as its own stated covariance,
// understated as a matched step's (λ_s), allows, must exceed test_chi2. With few closures a perfect
// odometry's misses (the closures' own 1–36 mrad on the Radish logs) fit λ_r or λ_c alike, and the
// fit's iterations settle on either; a free λ_c would pass a drifting odometry's misses off as the
// closures' own error just as well.
double HeadingScale(const std::vector<ChainMisses>& closures,
                    const std::vector<ChainMisses>& stretches, double test_chi2) {
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
  if (!(x(0) > 0.0) || !(test_chi2 > 0.0)) return x(0);
  // The test: each closure errs only as its own covariance says, understated as a matched step's
  // (λ_s), with λ_r and without it (no free variance of its own, to pass an odometry's drift off
  // as the closures' error). The closures' two misses each come first, in their order.
  std::vector<VarianceObservation> with = observations;
  for (std::size_t i = 0; i < closures.size(); ++i) {
    const ChainMisses& m = closures[i];
    const double own = m.closure_covariance(2, 2);
    with[2 * i].design = Eigen::Vector3d(m.odometry_per_heading(2, 2), own, 0.0);
    with[2 * i + 1].design = Eigen::Vector3d(0.0, m.matched_covariance(2, 2) + own, 0.0);
  }
  std::vector<VarianceObservation> without = with;
  for (VarianceObservation& o : without) o.design(0) = 0.0;
  const double statistic =
      2.0 * (VarianceComponentsLogLikelihood(with, FitVarianceComponents(with)) -
             VarianceComponentsLogLikelihood(without, FitVarianceComponents(without)));
  return statistic > test_chi2 ? x(0) : 0.0;
}

// A position miss: its squared length, expected to be the trace of its covariance.
VarianceObservation PositionMiss(const Eigen::Vector3d& miss, const Eigen::Matrix3d& known,
                                 const Eigen::VectorXd& design) {
  return {miss.head<2>().squaredNorm(), known.topLeftCorner<2, 2>().trace(), design, 2.0};
}

// λ_t on the stretches alone, beside λ_j (the matching's jitter at a stretch's two ends), the
// heading's part at λ_r and the matched chain's at λ_s counted in. The stretches cannot tell the
// odometry's noise from what the matched chain drifts beyond λ_s: an upper bound.
double PositionScaleOnStretches(const std::vector<ChainMisses>& stretches, double heading_scale,
                                double matched_scale) {
  std::vector<VarianceObservation> observations;
  for (const ChainMisses& m : stretches)
    observations.push_back(
        PositionMiss(m.odometry_miss,
                     heading_scale * m.odometry_per_heading + m.odometry_floor +
                         matched_scale * m.matched_covariance,
                     Eigen::Vector2d(m.odometry_per_position.topLeftCorner<2, 2>().trace(), 2.0)));
  return FitVarianceComponents(observations)(0);
}

// λ_t from the three sources in position, as the heading's (λ_t, the matched chain's position
// scale, the closure's own error, the jitter of a stretch's ends; the heading's part at λ_r), and
// how well they know it. Over a loop the heading's lever dominates a drifting odometry's position
// misses: there the closures hardly see λ_t, and its bound is wide.
double PositionScaleUpperBound(const std::vector<ChainMisses>& closures,
                               const std::vector<ChainMisses>& stretches, double heading_scale) {
  std::vector<VarianceObservation> observations;
  auto trace = [](const Eigen::Matrix3d& m) { return m.topLeftCorner<2, 2>().trace(); };
  for (const ChainMisses& m : closures) {
    observations.push_back(
        PositionMiss(m.odometry_miss, heading_scale * m.odometry_per_heading + m.odometry_floor,
                     Eigen::Vector4d(trace(m.odometry_per_position), 0.0, 2.0, 0.0)));
    observations.push_back(
        PositionMiss(m.matched_miss, Eigen::Matrix3d::Zero(),
                     Eigen::Vector4d(0.0, trace(m.matched_covariance), 2.0, 0.0)));
  }
  for (const ChainMisses& m : stretches)
    observations.push_back(PositionMiss(
        m.odometry_miss, heading_scale * m.odometry_per_heading + m.odometry_floor,
        Eigen::Vector4d(trace(m.odometry_per_position), trace(m.matched_covariance), 0.0, 2.0)));
  const Eigen::VectorXd x = FitVarianceComponents(observations);
  const double variance = VarianceComponentsCovariance(observations, x)(0, 0);
  return x(0) + kBoundSigmas * std::sqrt(std::max(variance, 0.0));
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
  heading_ = HeadingScale(misses_, stretches_, options_.heading_test_chi2);
  position_ = stretches_.empty()
                  ? 0.0
                  : std::min(PositionScaleOnStretches(stretches_, heading_, matched_),
                             PositionScaleUpperBound(misses_, stretches_, heading_));
  position_ = std::max(position_, options_.position_per_heading_m2 * heading_);
}

Eigen::Matrix3d OdometryModel::StepCovariance(const Pose2D& increment) const {
  const OdometryStepShape shape = Shape(increment);
  return (position_ * shape.position + heading_ * shape.heading + shape.floor) / matched_;
}

}  // namespace scanloc
