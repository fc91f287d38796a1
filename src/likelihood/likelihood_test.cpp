#include "scanloc/likelihood/likelihood_test.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

namespace scanloc {
namespace {

void Require(bool condition, const std::string& message) {
  if (!condition) throw std::invalid_argument("LikelihoodTestOptions: " + message);
}

}  // namespace

void LikelihoodTestOptions::Validate() const {
  Require(slot_count >= 2 && slot_count <= 100000, "slot_count (NS) must be in [2, 100000]");
  Require(std::isfinite(slot_width_m) && slot_width_m > 0.0,
          "slot_width_m (Δslot) must be positive and finite");
  Require(std::isfinite(match_threshold_m) && match_threshold_m > 0.0,
          "match_threshold_m (T_Map) must be positive and finite");
  Require(std::isfinite(last_slot_distance_m) && last_slot_distance_m >= 0.0,
          "last_slot_distance_m (Δmax) must be finite and >= 0 (0 selects 3/2·NS·Δslot)");
}

LikelihoodTestResult RunLikelihoodTest(const LaserScan& scan, const SimulatedScan& simulated,
                                       const LikelihoodTestOptions& options) {
  options.Validate();
  if (scan.size() != simulated.size())
    throw std::invalid_argument("RunLikelihoodTest: the scan has " + std::to_string(scan.size()) +
                                " beams, the simulated scan " + std::to_string(simulated.size()));
  const int ns = options.slot_count;
  const double last_slot_start = (ns - 1) * options.slot_width_m;
  LikelihoodTestResult result;
  result.histogram.assign(ns, 0);
  for (std::size_t i = 0; i < scan.size(); ++i) {
    // Step 2: both ranges valid.
    if (!scan.IsValid(i) || !simulated.IsValid(i)) continue;
    ++result.valid_pairs;
    // Steps 3–6.
    const double distance = std::abs(scan.ranges_m[i] - simulated.ranges_m[i]);
    if (distance > options.match_threshold_m) continue;
    const int slot = distance > last_slot_start
                         ? ns - 1
                         : std::min(ns - 1, static_cast<int>(distance / options.slot_width_m));
    ++result.histogram[slot];
  }
  double first = 0.0, second = 0.0;
  for (int k = 0; k < ns; ++k) {
    result.match_pairs += result.histogram[k];                           // (3.8)
    const double centre = k < ns - 1 ? options.slot_width_m * (k + 0.5)  // (3.9) slot centres
                                     : options.LastSlotDistance();       // Δmax for the last
    first += result.histogram[k] * centre;
    // (3.10) prints the last term as (t·Δmax)²; a second moment needs t·Δmax², used here.
    second += result.histogram[k] * centre * centre;
  }
  if (result.match_pairs > 0) {
    result.expect_value_m = first / result.match_pairs;
    result.dispersion_m2 = second / result.match_pairs;
  }
  return result;
}

}  // namespace scanloc
