#include "scanloc/graph/odometry_model.hpp"

#include "scanloc/graph/paired_misses.hpp"
#include "scanloc/graph/variance_components.hpp"

#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
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
        position_per_heading_m2 >= 0.0 && heading_test_chi2 >= 0.0 && position_test_chi2 >= 0.0) ||
      !std::isfinite(turn_weight_m_per_rad + floor_m + floor_rad + stretch_m +
                     position_per_heading_m2 + heading_test_chi2 + position_test_chi2))
    throw std::invalid_argument(
        "OdometryModelOptions: turn_weight_m_per_rad, position_per_heading_m2 and the "
        "tests' chi2 must be >= 0, the floors and stretch_m positive");
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

namespace {

// Where a test's statistic is tested again without its most decisive closure: at the bound it is
// compared with (none when the test is off).
double TestBound(double test_chi2) {
  return test_chi2 > 0.0 ? test_chi2 : std::numeric_limits<double>::infinity();
}

// Each closure's two misses in heading as one observation, and the stretches' (paired_misses.hpp).
std::vector<PairedMiss<1>> PairedHeadings(const std::vector<ChainMisses>& closures) {
  std::vector<PairedMiss<1>> paired(closures.size());
  for (std::size_t i = 0; i < closures.size(); ++i) {
    const ChainMisses& m = closures[i];
    PairedMiss<1>& p = paired[i];
    p.odometry_miss(0) = m.odometry_miss(2);
    p.matched_miss(0) = m.matched_miss(2);
    p.odometry_known(0, 0) = m.odometry_floor(2, 2);
    p.odometry_shape(0, 0) = m.odometry_per_heading(2, 2);
    p.matched_shape(0, 0) = m.matched_covariance(2, 2);
    p.closure_known(0, 0) = m.closure_covariance(2, 2);
    p.closure_shape(0, 0) = 2.0;
  }
  return paired;
}

std::vector<StretchMiss<1>> StretchHeadings(const std::vector<ChainMisses>& stretches) {
  std::vector<StretchMiss<1>> misses(stretches.size());
  for (std::size_t i = 0; i < stretches.size(); ++i) {
    const ChainMisses& m = stretches[i];
    misses[i].miss(0) = m.odometry_miss(2);
    misses[i].known(0, 0) = m.odometry_floor(2, 2);
    misses[i].odometry_shape(0, 0) = m.odometry_per_heading(2, 2);
    misses[i].matched_shape(0, 0) = m.matched_covariance(2, 2);
    misses[i].jitter_shape(0, 0) = 2.0;
    misses[i].start_m = m.start_path_m;
    misses[i].end_m = m.start_path_m + m.path_m;
  }
  return misses;
}

// The odometry's heading noise λ_r, and the matching's jitter in heading (rad², at each matched
// posture) that the paired test found beside it.
struct HeadingFit {
  double scale = 0.0, jitter = 0.0, statistic = 0.0;
};

// λ_r from three sources compared two by two in heading (variance_components.hpp): each
// closure against the odometry chain (λ_r and the closure's own error, a variance λ_c alike for
// every closure) and against the matched chain (λ_s and λ_c), each stretch the odometry chain
// against the matched one (λ_r and λ_s). A perfect odometry's closures miss by their own error,
// which no longer passes for the odometry's. λ_r is zero unless the paired test
// (paired_misses.hpp) rejects zero: with few closures a perfect odometry's misses (the closures'
// own 1–36 mrad on the Radish logs) fit λ_r or λ_c alike, and the fit's iterations settle on
// either. The test sees each closure's error in both its misses, and lets it be no larger than a
// matched posture's jitter, learned from the stretches: a free closure error would pass a
// drifting odometry's misses off as the closures' own (Intel, under perturbations of the
// defaults, was lost 5 times in 10 that way). The jitter is returned for the position's test.
HeadingFit FitHeading(const std::vector<ChainMisses>& closures,
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
  const double fitted = FitVarianceComponents(observations)(0);
  const NoiseTest test = TestOdometryNoise<1>(PairedHeadings(closures), StretchHeadings(stretches),
                                              TestBound(test_chi2));
  const bool noisy = fitted > 0.0 && (!(test_chi2 > 0.0) || test.statistic > test_chi2);
  return {noisy ? fitted : 0.0, noisy ? test.with.jitter : test.without.jitter, test.statistic};
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

// How far the misses in position reject an odometry whose position noise is only `least` (m²/m,
// what its heading noise implies): the heading's paired test (paired_misses.hpp) on each
// closure's two position misses, the stretches' ends jittering as a matched scan does, the
// heading's part at λ_r. Without it, a perfect odometry's position noise was what the fit of a
// few closures settled on: one closure's few centimetres made it 2e-4 m²/m (edmonton).
double PositionStatistic(const std::vector<ChainMisses>& closures,
                         const std::vector<ChainMisses>& stretches, const HeadingFit& heading,
                         double least, double test_chi2) {
  const auto known = [&](const ChainMisses& m) -> Eigen::Matrix2d {
    return (heading.scale * m.odometry_per_heading + least * m.odometry_per_position +
            m.odometry_floor)
        .topLeftCorner<2, 2>();
  };
  // A heading jitter at the start turns the whole way to the end about it.
  const auto lever = [&](const ChainMisses& m) -> Eigen::Matrix2d {
    const Eigen::Vector2d across(-m.translation_m.y(), m.translation_m.x());
    return heading.jitter * across * across.transpose();
  };
  std::vector<PairedMiss<2>> paired(closures.size());
  for (std::size_t i = 0; i < closures.size(); ++i) {
    const ChainMisses& m = closures[i];
    paired[i].odometry_miss = m.odometry_miss.head<2>();
    paired[i].matched_miss = m.matched_miss.head<2>();
    paired[i].odometry_known = known(m);
    paired[i].odometry_shape = m.odometry_per_position.topLeftCorner<2, 2>();
    paired[i].matched_shape = m.matched_covariance.topLeftCorner<2, 2>();
    paired[i].closure_known = m.closure_covariance.topLeftCorner<2, 2>() + lever(m);
    paired[i].closure_shape = 2.0 * Eigen::Matrix2d::Identity();
  }
  std::vector<StretchMiss<2>> misses(stretches.size());
  for (std::size_t i = 0; i < stretches.size(); ++i) {
    const ChainMisses& m = stretches[i];
    misses[i].miss = m.odometry_miss.head<2>();
    misses[i].known = known(m) + lever(m);
    misses[i].odometry_shape = m.odometry_per_position.topLeftCorner<2, 2>();
    misses[i].matched_shape = m.matched_covariance.topLeftCorner<2, 2>();
    misses[i].jitter_shape = 2.0 * Eigen::Matrix2d::Identity();
    misses[i].start_m = m.start_path_m;
    misses[i].end_m = m.start_path_m + m.path_m;
  }
  return TestOdometryNoise<2>(paired, misses, TestBound(test_chi2)).statistic;
}

}  // namespace

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
  const HeadingFit heading = FitHeading(misses_, stretches_, options_.heading_test_chi2);
  heading_ = heading.scale;
  heading_statistic_ = heading.statistic;
  heading_jitter_ = heading.jitter;
  position_statistic_.reset();
  position_ = stretches_.empty()
                  ? 0.0
                  : std::min(PositionScaleOnStretches(stretches_, heading_, matched_),
                             PositionScaleUpperBound(misses_, stretches_, heading_));
  const double least = options_.position_per_heading_m2 * heading_;
  if (position_ > least && options_.position_test_chi2 > 0.0) {
    position_statistic_ =
        PositionStatistic(misses_, stretches_, heading, least, options_.position_test_chi2);
    if (!(*position_statistic_ > options_.position_test_chi2)) position_ = least;
  }
  position_ = std::max(position_, least);
}

Eigen::Matrix3d OdometryModel::StepCovariance(const Pose2D& increment) const {
  const OdometryStepShape shape = Shape(increment);
  return (position_ * shape.position + heading_ * shape.heading + shape.floor) / matched_;
}

}  // namespace scanloc
