#pragma once
// Variance components: several sources of error, each contributing a variance that is a known
// shape times an unknown scale, observed only through differences of their measurements. Given
// squared misses, each expected to be known + Σ_j design_j · scale_j, it finds the scales (all
// ≥ 0) by iteratively reweighted least squares: each squared miss weighed by the inverse square
// of the variance the scales predict for it (a squared Gaussian's variance is twice the square
// of its own), misses beyond the 99.9 % quantile of χ² with one degree of freedom left out once
// the fit has settled. Three sources compared two by two (the three-cornered hat) tell each one's
// scale apart, where one comparison alone gives only their sum.

#include <Eigen/Core>
#include <vector>

namespace scanloc {

struct VarianceObservation {
  double squared_miss = 0.0;
  double known = 0.0;      // the part of its expected value no scale multiplies
  Eigen::VectorXd design;  // what each scale multiplies (one entry per scale, >= 0)
  // The squared length of a miss of k independent parts alike: its variance is 2v²/k for an
  // expected value v (a squared Gaussian's, k = 1).
  double degrees_of_freedom = 1.0;
};

// The scales, one per design entry (all observations have as many). Zero for a scale no
// observation needs; empty without observations.
Eigen::VectorXd FitVarianceComponents(const std::vector<VarianceObservation>& observations);

// The log-likelihood of the squared misses under `scales`, up to a constant: each miss's squared
// length a multiple v of χ² with its degrees of freedom k contributes −k/2·(ln v + miss²/v), the
// whitened miss²/v capped at 10.83 (χ²₁'s 99.9 % quantile, where the fit starts to bound a miss's
// pull), so that one wild miss cannot decide a comparison. Twice the difference between two fits,
// one with a scale held at zero, is the likelihood-ratio statistic of that scale (χ²₁ under zero).
double VarianceComponentsLogLikelihood(const std::vector<VarianceObservation>& observations,
                                       const Eigen::VectorXd& scales);

// The covariance of the scales at `scales`: the inverse of their Fisher information under the
// observations. A scale the observations cannot tell from the others (its shape a combination of
// theirs) has a variance that is infinite, or nearly: what the fit chose for it is not known.
Eigen::MatrixXd VarianceComponentsCovariance(const std::vector<VarianceObservation>& observations,
                                             const Eigen::VectorXd& scales);

}  // namespace scanloc
