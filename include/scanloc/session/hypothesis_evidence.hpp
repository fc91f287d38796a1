#pragma once
// The evidence that tells two held hypotheses apart (§3.3, last paragraph: "confirm or discard them
// as the system progresses"). Every hypothesis is localised at the same scans, so their costs at
// those scans pair up; one whose cost exceeded the other's by more than the scan-to-scan spread of
// the differences explains can be discarded, whatever the rules said of each scan alone: a
// one-sided paired Student t-test at 99.9 %. A steady excess of a few percent is no evidence
// against a place, though: a refinement that settled a centimetre off its place's best fit costs
// that much more at every scan, so the excess must also reach a fraction of the cheaper's cost.
//
// The cost compared is the truncated mean distance, not (3.11). (3.11) charges a pair pushed
// beyond T_Map α/NVP and drops its distance from ExpectValue, so a place that explains a scan's
// loose pairs by leaving them unmatched can cost less than the place that matches them (on Intel,
// on a loop-closed map, a look-alike 24 m away matched 63 % of the pairs at 0.107 m and cost 7 %
// less than the true place, which matched 91 % at 0.145 m). The truncated mean counts each
// unmatched pair as T_Map and never rewards losing a match. Where the map lacks much of what the
// robot sees it can prefer a look-alike that matches more (on ACES a corridor seen from its other
// end, 0.81 of the pairs against the true place's 0.75); docs/BENCHMARKS.md measures both costs.

#include <cstddef>
#include <vector>

#include "scanloc/likelihood/likelihood_test.hpp"
#include "scanloc/session/scan_processor.hpp"

namespace scanloc {

// The mean over the valid pairs of each pair's distance, one beyond T_Map counted as T_Map:
// MatchRatio · ExpectValue + (1 − MatchRatio) · T_Map; +∞ without a valid pair.
double TruncatedMeanDistance(const LikelihoodTestResult& test, double match_threshold_m);

// Records the cost of `h` at scan `scan` (its TruncatedMeanDistance); a non-finite cost (a scan
// that left it no refinement) is not recorded. Only the newest kMaxCostHistory costs are kept.
void RecordCost(Hypothesis& h, std::size_t scan, double cost, double expect_value_m = 0.0,
                double match_ratio = 0.0);
inline constexpr std::size_t kMaxCostHistory = 10;

struct CostComparison {
  int scans = 0;              // scans at which both were localised (up to kMaxCostHistory)
  double mean_excess = 0.0;   // mean of costlier.cost − cheaper.cost over them
  double t = 0.0;             // the paired t statistic of that mean
  double cheaper_mean = 0.0;  // mean of cheaper.cost over them
  // t beyond the one-sided 99.9 % quantile, scans >= min_scans and mean_excess at least
  // min_excess_ratio · cheaper_mean.
  bool decided = false;
};

// Whether `costlier` cost more than `cheaper` at the scans both were localised at, beyond chance
// and by at least min_excess_ratio of the cheaper's cost.
CostComparison CompareCosts(const Hypothesis& costlier, const Hypothesis& cheaper, int min_scans,
                            double min_excess_ratio);
// The same test on another series of the history: the expected value or the match ratio.
CostComparison CompareSeries(const Hypothesis& costlier, const Hypothesis& cheaper,
                             double CostAt::*series, int min_scans, double min_excess_ratio);

// Whether `other` outmatched `h` at the scans both were localised at: it matched the pairs
// tighter beyond chance (expected value lower, CompareSeries, by min_excess_ratio of its own at
// least) and its truncated mean was lower too on average there, if by less than CompareCosts
// would decide. The truncated mean weighs an unmatched pair as T_Map, ten times a matched one's
// typical distance: on ACES's alike corridors the true place matches as many pairs 30 % tighter
// than a look-alike and costs only 7 % less by it, inside the twin rooms' margin. A place that
// matches fewer pairs tighter (Intel's corridor look-alikes, a look-alike 7 m along an ACES
// corridor) has the higher truncated mean and is never outmatching.
bool Outmatched(const Hypothesis& h, const Hypothesis& other, int min_scans,
                double min_excess_ratio);
// The same from the two comparisons of h against other it rests on: the expected value's
// (`looser`) and the truncated mean's (`costlier`, CompareCosts).
bool Outmatched(const CostComparison& looser, const CostComparison& costlier);
// Whether `h` matched its pairs tighter than `other` beyond chance, by min_excess_ratio at least
// (the expected value's CompareSeries): then other's lower truncated mean is evidence the other
// way, and the localiser discards neither by it.
bool MatchedTighter(const Hypothesis& h, const Hypothesis& other, int min_scans,
                    double min_excess_ratio);

// Rule 3 among the held hypotheses at one scan: each validated one whose (3.11) cost exceeds
// max_cost_ratio × the cheapest validated one's is no longer validated (verdict kHighCost). The
// result says, per hypothesis, whether that scan counts towards its discarding: every scan but
// one whose rejection is excused, which is one where `needs_truncated_mean` holds and its truncated
// mean distance is no higher than the cheapest's (on Intel's corridors a posture 1–2.5 m off
// matches fewer beams more tightly and costs less by (3.11) at many scans, while the true one has
// the lower truncated mean at nearly every scan: docs/BENCHMARKS.md).
// Which of the ranked hypotheses (best first) the output follows: the one within same_m and
// same_rad of `followed` (the posture output at the scan before, carried by the odometry; the
// nearest if several) while it is validated and the best ranked did not cost at least
// min_excess_ratio less than it at the scans both were localised at; else the best (0).
std::size_t SteadyOutput(const std::vector<Hypothesis>& ranked, const Pose2D& followed,
                         double same_m, double same_rad, double min_excess_ratio);

std::vector<bool> JudgeRelativeCost(std::vector<Hypothesis>& held, double max_cost_ratio,
                                    bool needs_truncated_mean);

// The order of held hypotheses, best first (the first is the output). One validated at the
// last scan comes first. Then, when `since` is a scan from which every hypothesis was costed at
// two scans or more (CommonSince), the one validated at more of those scans, then the one whose
// mean truncated mean distance there is lower: the places are judged on the scans all were
// tested at, not on what the older did alone. Otherwise, and on ties, the one validated at more
// scans in all, more in a row, then cheaper at the last scan. On ACES, a look-alike found first
// led a place cheaper at every scan both were tested at, for 100 scans of a robot standing still
// (docs/BENCHMARKS.md).
bool RanksBefore(const Hypothesis& a, const Hypothesis& b, std::size_t since);

// The first scan of the newest cost history among `hypotheses`, from which every one of them was
// held, when each was costed at two scans or more from there; SIZE_MAX otherwise (and then no
// common scans are compared, for any pair: the order stays one order).
std::size_t CommonSince(const std::vector<Hypothesis>& hypotheses);

// The one-sided 99.9 % quantile of Student's t with `dof` degrees of freedom (dof >= 1).
double StudentT999(int dof);

}  // namespace scanloc
