#include "scanloc/session/hypothesis_evidence.hpp"

#include <algorithm>
#include <cmath>
#include <iterator>
#include <limits>

namespace scanloc {

double TruncatedMeanDistance(const LikelihoodTestResult& test, double match_threshold_m) {
  if (test.valid_pairs <= 0) return HUGE_VAL;
  const double ratio = test.MatchRatio();
  return ratio * test.expect_value_m + (1.0 - ratio) * match_threshold_m;
}

void RecordCost(Hypothesis& h, std::size_t scan, double cost, double expect_value_m,
                double match_ratio) {
  if (!std::isfinite(cost)) return;
  const CostAt at{scan, cost, expect_value_m, match_ratio};
  if (!h.costs.empty() && h.costs.back().scan == scan) {
    h.costs.back() = at;  // localised twice at one scan (tracked, then found by a search)
    return;
  }
  h.costs.push_back(at);
  if (h.costs.size() > kMaxCostHistory) h.costs.erase(h.costs.begin());
}

double StudentT999(int dof) {
  // Student's t, one-sided 0.999 quantiles for 1..30 degrees of freedom, then the normal's.
  static constexpr double kTable[] = {318.31, 22.327, 10.215, 7.173, 5.893, 5.208, 4.785, 4.501,
                                      4.297,  4.144,  4.025,  3.930, 3.852, 3.787, 3.733, 3.686,
                                      3.646,  3.610,  3.579,  3.552, 3.527, 3.505, 3.485, 3.467,
                                      3.450,  3.435,  3.421,  3.408, 3.396, 3.385};
  if (dof < 1) return HUGE_VAL;
  if (dof <= static_cast<int>(std::size(kTable))) return kTable[dof - 1];
  return 3.090;
}

CostComparison CompareCosts(const Hypothesis& costlier, const Hypothesis& cheaper, int min_scans,
                            double min_excess_ratio) {
  return CompareSeries(costlier, cheaper, &CostAt::cost, min_scans, min_excess_ratio);
}

bool MatchedTighter(const Hypothesis& h, const Hypothesis& other, int min_scans,
                    double min_excess_ratio) {
  return CompareSeries(other, h, &CostAt::expect_value_m, min_scans, min_excess_ratio).decided;
}

bool Outmatched(const Hypothesis& h, const Hypothesis& other, int min_scans,
                double min_excess_ratio) {
  const CostComparison looser =
      CompareSeries(h, other, &CostAt::expect_value_m, min_scans, min_excess_ratio);
  if (!looser.decided) return false;
  return Outmatched(looser, CompareCosts(h, other, min_scans, min_excess_ratio));
}

bool Outmatched(const CostComparison& looser, const CostComparison& costlier) {
  // ... and the truncated mean agrees, on average over the same scans.
  return looser.decided && costlier.mean_excess > 0.0;
}

CostComparison CompareSeries(const Hypothesis& costlier, const Hypothesis& cheaper,
                             double CostAt::*series, int min_scans, double min_excess_ratio) {
  std::vector<double> excess;
  double cheaper_sum = 0.0;
  auto a = costlier.costs.begin();
  auto b = cheaper.costs.begin();
  while (a != costlier.costs.end() && b != cheaper.costs.end()) {
    if (a->scan < b->scan) {
      ++a;
    } else if (b->scan < a->scan) {
      ++b;
    } else {
      cheaper_sum += (*b).*series;
      excess.push_back((*a++).*series - (*b++).*series);
    }
  }
  CostComparison out;
  out.scans = static_cast<int>(excess.size());
  if (out.scans < 2) return out;
  const double n = static_cast<double>(out.scans);
  double sum = 0.0;
  for (double d : excess) sum += d;
  out.mean_excess = sum / n;
  out.cheaper_mean = cheaper_sum / n;
  double squares = 0.0;
  for (double d : excess) squares += (d - out.mean_excess) * (d - out.mean_excess);
  const double spread = std::sqrt(squares / (n - 1.0));
  out.t = spread > 0.0 ? out.mean_excess * std::sqrt(n) / spread
                       : (out.mean_excess > 0.0 ? HUGE_VAL : 0.0);
  out.decided = out.scans >= std::max(2, min_scans) && out.t > StudentT999(out.scans - 1) &&
                out.mean_excess >= min_excess_ratio * out.cheaper_mean;
  return out;
}

std::vector<bool> JudgeRelativeCost(std::vector<Hypothesis>& held, double max_cost_ratio,
                                    bool needs_truncated_mean) {
  const Hypothesis* cheapest = nullptr;
  for (const Hypothesis& h : held)
    if (h.validated && (!cheapest || h.cost < cheapest->cost)) cheapest = &h;
  std::vector<bool> counts(held.size(), true);
  if (!cheapest) return counts;
  const double best_cost = cheapest->cost;
  const double best_truncated_mean_m = cheapest->truncated_mean_m;
  for (std::size_t i = 0; i < held.size(); ++i) {
    Hypothesis& h = held[i];
    if (!h.validated || !(h.cost > max_cost_ratio * best_cost)) continue;
    h.validated = false;
    h.verdict = Verdict::kHighCost;
    counts[i] = !(needs_truncated_mean && h.truncated_mean_m <= best_truncated_mean_m);
  }
  return counts;
}

namespace {

struct CostsSince {
  int scans = 0;
  double mean = HUGE_VAL;
};

CostsSince Since(const Hypothesis& h, std::size_t since) {
  CostsSince out;
  double sum = 0.0;
  for (const CostAt& c : h.costs)
    if (c.scan >= since) {
      sum += c.cost;
      ++out.scans;
    }
  if (out.scans > 0) out.mean = sum / out.scans;
  return out;
}

}  // namespace

std::size_t CommonSince(const std::vector<Hypothesis>& hypotheses) {
  constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
  std::size_t since = 0;
  for (const Hypothesis& h : hypotheses) {
    if (h.costs.empty()) return kNone;
    since = std::max(since, h.costs.front().scan);
  }
  for (const Hypothesis& h : hypotheses)
    if (Since(h, since).scans < 2) return kNone;
  return since;
}

std::size_t SteadyOutput(const std::vector<Hypothesis>& ranked, const Pose2D& followed,
                         double same_m, double same_rad, double min_excess_ratio) {
  std::size_t kept = ranked.size();
  double nearest_m = HUGE_VAL;
  for (std::size_t i = 0; i < ranked.size(); ++i) {
    const Pose2D d = Between(followed, ranked[i].T_world_robot);
    const double distance_m = std::hypot(d.x_m, d.y_m);
    if (distance_m < same_m && std::abs(d.yaw_rad) < same_rad && distance_m < nearest_m) {
      kept = i;
      nearest_m = distance_m;
    }
  }
  if (kept == ranked.size() || kept == 0 || !ranked[kept].validated) return 0;
  const CostComparison c = CompareCosts(ranked[kept], ranked.front(), 2, min_excess_ratio);
  const bool cheaper = c.scans >= 2 && c.mean_excess >= min_excess_ratio * c.cheaper_mean;
  return cheaper ? 0 : kept;
}

bool RanksBefore(const Hypothesis& a, const Hypothesis& b, std::size_t since) {
  if (a.validated != b.validated) return a.validated;
  const CostsSince ca = Since(a, since), cb = Since(b, since);
  if (ca.scans >= 2 && cb.scans >= 2) {
    const int va = std::min(a.confirmed_in_row, ca.scans);
    const int vb = std::min(b.confirmed_in_row, cb.scans);
    if (va != vb) return va > vb;
    if (ca.mean != cb.mean) return ca.mean < cb.mean;
  }
  if (a.confirmations != b.confirmations) return a.confirmations > b.confirmations;
  if (a.confirmed_in_row != b.confirmed_in_row) return a.confirmed_in_row > b.confirmed_in_row;
  return a.truncated_mean_m < b.truncated_mean_m;
}

}  // namespace scanloc
