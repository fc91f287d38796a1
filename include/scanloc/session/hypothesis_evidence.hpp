#pragma once
// The evidence that tells two held hypotheses apart (§3.3, last paragraph: "confirm or discard them
// as the system progresses"). Every hypothesis is localised at the same scans, so their costs
// (3.11) at those scans pair up; one whose cost exceeded the other's by more than the scan-to-scan
// spread of the differences explains can be discarded, whatever the rules said of each scan alone:
// a one-sided paired Student t-test at 99.9 %. A steady excess of a few percent is no evidence
// against a place, though: a refinement that settled a centimetre off its place's best fit costs
// that much more at every scan, so the excess must also reach a fraction of the cheaper's cost.

#include <cstddef>
#include <vector>

#include "scanloc/session/scan_processor.hpp"

namespace scanloc {

// Records the cost (3.11) of `h` at scan `scan`; a scan that left it no refinement is not recorded.
// Only the newest kMaxCostHistory costs are kept.
void RecordCost(Hypothesis& h, std::size_t scan, double cost);
inline constexpr std::size_t kMaxCostHistory = 10;

struct CostComparison {
  int scans = 0;             // scans at which both were localised (up to kMaxCostHistory)
  double mean_excess = 0.0;  // mean of costlier.cost − cheaper.cost over them
  double t = 0.0;            // the paired t statistic of that mean
  double cheaper_mean = 0.0;  // mean of cheaper.cost over them
  // t beyond the one-sided 99.9 % quantile, scans >= min_scans and mean_excess at least
  // min_excess_ratio · cheaper_mean.
  bool decided = false;
};

// Whether `costlier` cost more than `cheaper` at the scans both were localised at, beyond chance
// and by at least min_excess_ratio of the cheaper's cost.
CostComparison CompareCosts(const Hypothesis& costlier, const Hypothesis& cheaper, int min_scans,
                            double min_excess_ratio);

// The one-sided 99.9 % quantile of Student's t with `dof` degrees of freedom (dof >= 1).
double StudentT999(int dof);

}  // namespace scanloc
