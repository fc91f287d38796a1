#include "scanloc/graph/variance_components.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>

namespace scanloc {
namespace {

// A squared miss beyond this many times its predicted variance pulls with a bounded force: its
// weight falls as the excess grows (Huber's weight on e²/v − 1; 10.83 is the 99.9 % quantile of
// χ² with 1 degree of freedom). Not left out: where a whole kind of misses disagrees with the
// scales, the scales are what is wrong.
constexpr double kChi2Quantile999 = 10.828;
constexpr int kIterations = 50;

// min Σ w (y − known − a·x)² over x ≥ 0, every subset of free scales tried (a few scales only).
Eigen::VectorXd NonNegativeLeastSquares(const std::vector<VarianceObservation>& observations,
                                        const std::vector<double>& weights) {
  const int n = static_cast<int>(observations.front().design.size());
  Eigen::VectorXd best = Eigen::VectorXd::Zero(n);
  double best_cost = std::numeric_limits<double>::infinity();
  for (unsigned subset = 0; subset < (1u << n); ++subset) {
    std::vector<int> free;
    for (int j = 0; j < n; ++j)
      if (subset & (1u << j)) free.push_back(j);
    Eigen::MatrixXd a(observations.size(), free.size());
    Eigen::VectorXd y(observations.size());
    for (std::size_t k = 0; k < observations.size(); ++k) {
      const double root = std::sqrt(weights[k]);
      for (std::size_t f = 0; f < free.size(); ++f)
        a(k, f) = root * observations[k].design(free[f]);
      y(k) = root * (observations[k].squared_miss - observations[k].known);
    }
    Eigen::VectorXd x = Eigen::VectorXd::Zero(n);
    double cost = y.squaredNorm();
    if (!free.empty()) {
      // Columns scaled to unit length: the scales' shapes differ by orders of magnitude.
      const Eigen::VectorXd norms = a.colwise().norm().transpose().cwiseMax(1e-300);
      const Eigen::MatrixXd scaled = a * norms.cwiseInverse().asDiagonal();
      const Eigen::VectorXd solved = scaled.colPivHouseholderQr().solve(y).cwiseQuotient(norms);
      if (!solved.allFinite() || solved.minCoeff() < 0.0) continue;
      for (std::size_t f = 0; f < free.size(); ++f) x(free[f]) = solved(f);
      cost = (y - a * solved).squaredNorm();
    }
    if (cost < best_cost) {
      best_cost = cost;
      best = x;
    }
  }
  return best;
}

// The squared misses' mean: a variance no scale reaches yet stays a tiny fraction of it, not 0.
double MeanSquaredMiss(const std::vector<VarianceObservation>& observations) {
  double mean = 0.0;
  for (const VarianceObservation& o : observations) mean += o.squared_miss;
  return std::max(mean / static_cast<double>(observations.size()), 1e-300);
}

}  // namespace

Eigen::VectorXd FitVarianceComponents(const std::vector<VarianceObservation>& observations) {
  if (observations.empty()) return {};
  const double mean = MeanSquaredMiss(observations);
  std::vector<double> weights(observations.size(), 1.0 / (mean * mean));
  Eigen::VectorXd scales = NonNegativeLeastSquares(observations, weights);
  for (int iteration = 1; iteration < kIterations; ++iteration) {
    for (std::size_t k = 0; k < observations.size(); ++k) {
      const VarianceObservation& o = observations[k];
      const double variance = std::max(o.known + o.design.dot(scales), 1e-9 * mean);
      const double excess = std::abs(o.squared_miss / variance - 1.0);
      weights[k] = std::min(1.0, kChi2Quantile999 / std::max(excess, 1e-12)) *
                   o.degrees_of_freedom / (variance * variance);
    }
    const Eigen::VectorXd next = NonNegativeLeastSquares(observations, weights);
    const bool settled = (next - scales).norm() <= 1e-9 * scales.norm();
    scales = next;
    if (settled) break;
  }
  return scales;
}

double VarianceComponentsLogLikelihood(const std::vector<VarianceObservation>& observations,
                                       const Eigen::VectorXd& scales) {
  if (observations.empty()) return 0.0;
  const double mean = MeanSquaredMiss(observations);
  double log_likelihood = 0.0;
  for (const VarianceObservation& o : observations) {
    const double variance = std::max(o.known + o.design.dot(scales), 1e-9 * mean);
    const double whitened = std::min(o.squared_miss / variance, kChi2Quantile999);
    log_likelihood -= 0.5 * o.degrees_of_freedom * (std::log(variance) + whitened);
  }
  return log_likelihood;
}

Eigen::MatrixXd VarianceComponentsCovariance(const std::vector<VarianceObservation>& observations,
                                             const Eigen::VectorXd& scales) {
  const Eigen::Index n = scales.size();
  Eigen::MatrixXd information = Eigen::MatrixXd::Zero(n, n);
  for (const VarianceObservation& o : observations) {
    const double variance = std::max(o.known + o.design.dot(scales), 1e-300);
    information +=
        (0.5 * o.degrees_of_freedom / (variance * variance)) * o.design * o.design.transpose();
  }
  // Inverted in the scales' own units (their shapes differ by orders of magnitude); a direction
  // the observations hardly see counts as unseen.
  const Eigen::VectorXd norms = information.diagonal().cwiseSqrt().cwiseMax(1e-300);
  const Eigen::MatrixXd scaled =
      norms.cwiseInverse().asDiagonal() * information * norms.cwiseInverse().asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eigen(scaled);
  const Eigen::VectorXd values =
      eigen.eigenvalues().cwiseMax(1e-12 * std::max(1.0, eigen.eigenvalues().maxCoeff()));
  const Eigen::MatrixXd inverse =
      eigen.eigenvectors() * values.cwiseInverse().asDiagonal() * eigen.eigenvectors().transpose();
  return norms.cwiseInverse().asDiagonal() * inverse * norms.cwiseInverse().asDiagonal();
}

}  // namespace scanloc
