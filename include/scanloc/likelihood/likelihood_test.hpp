#pragma once
// §3.3 The Likelihood Test: the histogram of point-to-point distances between a real scan and the
// scan simulated at a candidate posture, and its moments.

#include <vector>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/simulation/simulated_scan.hpp"

namespace scanloc {

struct LikelihoodTestOptions {
  int slot_count = 20;             // NS: number of histogram slots
  double slot_width_m = 0.01;      // Δslot
  double match_threshold_m = 0.5;  // T_Map: a pair farther apart than this is not a match pair
  // Δmax: the distance that stands for the last slot; ≤ 0 selects §3.3's default 3/2·NS·Δslot.
  double last_slot_distance_m = 0.0;

  double LastSlotDistance() const {
    return last_slot_distance_m > 0.0 ? last_slot_distance_m : 1.5 * slot_count * slot_width_m;
  }
  // Throws std::invalid_argument naming the first option out of its domain.
  void Validate() const;
};

struct LikelihoodTestResult {
  int valid_pairs = 0;          // NVP: both ranges valid
  int match_pairs = 0;          // (3.8) MatchPairs: valid pairs within T_Map
  std::vector<int> histogram;   // t_0 … t_{NS−1}
  double expect_value_m = 0.0;  // (3.9) ExpectValue; 0 when there is no match pair
  double dispersion_m2 = 0.0;   // (3.10) Disp, second moment about zero
  double MatchRatio() const {
    return valid_pairs > 0 ? static_cast<double>(match_pairs) / valid_pairs : 0.0;
  }
};

// Compares the real scan with a simulated one, beam by beam (the layouts must have equal beam
// counts; throws std::invalid_argument otherwise).
LikelihoodTestResult RunLikelihoodTest(const LaserScan& scan, const SimulatedScan& simulated,
                                       const LikelihoodTestOptions& options = {});

}  // namespace scanloc
