#pragma once
// The laser signature (§3.1.3): the distribution of the point-to-point distances of confirmed
// scans, learned online over a session. The chapter calls absolute criteria inadequate across
// lasers and places and proposes judging a candidate by how close its histogram is to the laser's
// own; here the signature is the recent confirmed scans' Likelihood Tests, and rule 2's E_max for
// the next scan follows from the spread of their expected values (median + k · robust σ). Until
// enough scans were confirmed, the configured E_max stands as the prior.

#include <cstddef>
#include <deque>
#include <vector>

#include "scanloc/common/sorted_window.hpp"
#include "scanloc/likelihood/likelihood_test.hpp"

namespace scanloc {

struct LaserSignatureOptions {
  // Confirmed scans the signature remembers (the most recent ones). It is the laser's signature,
  // so it needs a long memory: with 50 scans, a hard stretch of confirmed but loose fits raised
  // the bound, which confirmed looser fits still (ACES: E_max up to 0.19 m, every run of the
  // robustness harness with a relation above 1 m); with 500, no run of it above 1 m
  // (docs/BENCHMARKS.md). 0 turns learning off (E_max stays the prior).
  int window = 500;
  // Confirmed scans needed before the learned bound replaces the prior E_max.
  int min_samples = 10;
  // The bound: median EV + spread_factor · 1.4826 · MAD(EV) (a robust σ). 3 keeps 99.7 % of a
  // normal spread.
  double spread_factor = 3.0;
  // Throws std::invalid_argument naming the first option out of its domain.
  void Validate() const;
};

class LaserSignature {
 public:
  explicit LaserSignature(LaserSignatureOptions options = {});

  // Learns from the Likelihood Test of a confirmed scan at its kept posture.
  void Add(const LikelihoodTestResult& confirmed);

  // Rule 2's bound for the next scan, metres: the learned one, or `prior_m` until min_samples
  // confirmed scans were seen. Never below prior_m (the prior is the laser's stated accuracy).
  double ExpectValueBound(double prior_m) const;

  std::size_t samples() const { return expect_values_m_.size(); }
  bool learned() const;
  // The mean normalised histogram of the remembered scans (empty before the first).
  std::vector<double> MeanHistogram() const;
  // The L1 distance between a test's normalised histogram and MeanHistogram(), in [0, 2]; 0 when
  // nothing was learned or the test has no valid pair.
  double HistogramDistance(const LikelihoodTestResult& test) const;

 private:
  LaserSignatureOptions options_;
  SortedWindow expect_values_m_;
  std::deque<std::vector<double>> histograms_;  // normalised, one per remembered scan
};

}  // namespace scanloc
