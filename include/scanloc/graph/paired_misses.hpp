#pragma once
// Does a log's odometry drift, or do its closures err? Each confirmed closure measures an old
// node's posture from a newer one, and the odometry chain and the matched chain each miss that
// measurement. Both misses hold the closure's own error, the same numbers in both: a closure that
// erred by 20 mrad makes both chains miss by about 20 mrad, with the same sign. A drifting odometry
// makes the odometry's miss alone large. Fitted as independent squared misses
// (variance_components.hpp), the two look alike, and a perfect odometry's closures (erring by
// 5–10 times their stated σ) passed for an odometry drifting at 1e-5 rad²/m, which kept its steps
// out of the graph. Here each closure's two misses are one observation with their joint
// covariance:
//   odometry miss: known + λ_o·O + E      cross term: E      matched miss: λ_s·M + E
// with E = C + λ_j·J the closure's error: C its stated covariance, J the shape of two matched
// postures' jitter. (O is the odometry chain's shape over the loop, M the matched chain's
// covariance.) Each stretch of the chain (the odometry chain against the matched one, no closure)
// is one more observation: known + λ_o·O + λ_s·M + λ_j·J, its two ends jittering alike. A closure
// errs as a scan matched on a map does, and the stretches measure how much that is: a free
// closure error would explain any odometry's misses where the matched chain drifts too far to
// vouch for the closures (a ring of tests/loop_closure_test.cpp; Intel under perturbations).
// The likelihood is maximised with and without λ_o, every scale ≥ 0; a squared Mahalanobis
// distance beyond the 99.9 % quantile of χ² counts as Huber's (growing with its root), so that one
// wild miss cannot decide. K = 1 for the heading, 2 for the position.

#include <Eigen/Core>
#include <cstddef>
#include <limits>
#include <optional>
#include <vector>

namespace scanloc {

template <int K>
struct PairedMiss {
  using Vector = Eigen::Matrix<double, K, 1>;
  using Matrix = Eigen::Matrix<double, K, K>;
  Vector odometry_miss = Vector::Zero(), matched_miss = Vector::Zero();
  Matrix odometry_known = Matrix::Zero();  // the odometry chain's variance no scale multiplies
  Matrix odometry_shape = Matrix::Zero();  // times λ_o
  Matrix matched_shape = Matrix::Zero();   // times λ_s
  Matrix closure_known = Matrix::Zero();   // the closure's stated covariance, in both misses
  Matrix closure_shape = Matrix::Zero();   // times λ_j, the matching's jitter, in both misses
};

// One stretch: the odometry chain minus the matched chain, no closure.
template <int K>
struct StretchMiss {
  using Vector = Eigen::Matrix<double, K, 1>;
  using Matrix = Eigen::Matrix<double, K, K>;
  Vector miss = Vector::Zero();
  Matrix known = Matrix::Zero(), odometry_shape = Matrix::Zero(), matched_shape = Matrix::Zero();
  Matrix jitter_shape = Matrix::Zero();  // times λ_j
  double start_m = 0.0, end_m = 0.0;     // where on the session's path it lies
};

struct PairedScales {
  double odometry = 0.0, matched = 0.0, jitter = 0.0;  // λ_o, λ_s, λ_j
};

// The log-likelihood of the misses under `scales`, up to a constant (robust as above).
template <int K>
double PairedLogLikelihood(const std::vector<PairedMiss<K>>& closures,
                           const std::vector<StretchMiss<K>>& stretches,
                           const PairedScales& scales);

// The likelihood-ratio test of the odometry's noise: the scales that maximise the likelihood with
// λ_o held at zero and with it free (λ_s and λ_j free in both), and twice the log-likelihood the
// second gains (χ² with 1 degree of freedom, or its half-mixture with 0, under a perfect odometry).
// All zero without closures.
// A statistic above `decisive_above` is tested again without the one event that gained the most
// from λ_o; when less than a quarter of the statistic is left, the test rested on that event, and
// the smaller stands (with that test's scales). The event is a closure (when three or more were
// made: with two, the one left would decide alone), or a place on the path: every stretch that
// overlaps the stretch whose own term gained the most. One event can be wrong, and a disproof
// resting on it is none:
// - acapulco, perfect odometry, a laser 1 cm noisier: a closure matched 1.3° off rejected the
//   odometry by itself (χ² 13.4), and the session followed its drifting matched chain.
// - edmonton, the same: the tracker took a turned candidate 10° off after 14 unconfirmed scans,
//   and the three stretches across that one step (of 131) rejected the odometry (χ² 103).
// A drifting odometry misses at every closure and along the whole path, and is rejected without
// any one of them (most of the time: the test has one closure less to see it by). Where the
// evidence is spread, one event's share is small and the test stands as made (ACES kept sparse,
// its real odometry: 11.35 without the most decisive place's four stretches of 148, 10.80).
struct NoiseTest {
  double statistic = 0.0;
  PairedScales without, with;
  std::optional<std::size_t> left_out_closure;  // its index, when the event left out was one
  std::size_t left_out_stretches = 0;           // when it was a place: how many stretches
};
template <int K>
NoiseTest TestOdometryNoise(const std::vector<PairedMiss<K>>& closures,
                            const std::vector<StretchMiss<K>>& stretches,
                            double decisive_above = std::numeric_limits<double>::infinity());

}  // namespace scanloc
