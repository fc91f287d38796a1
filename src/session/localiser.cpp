#include "scanloc/session/localiser.hpp"

#include "scanloc/session/hypothesis_evidence.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <numeric>
#include <stdexcept>
#include <string>

namespace scanloc {
namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

void Count(Hypothesis& h) {
  if (h.validated) {
    ++h.confirmed_in_row;
    ++h.confirmations;
    h.unconfirmed_in_row = 0;
  } else {
    h.confirmed_in_row = 0;
    ++h.unconfirmed_in_row;
  }
}

// The odometry moved more than the session's localise gate since `from` (or either is unknown).
bool MovedSince(const std::optional<Pose2D>& from, const Iteration& iteration,
                const SessionOptions& options) {
  if (!from || !iteration.odometry) return true;
  const Pose2D d = Between(*from, *iteration.odometry);
  return std::hypot(d.x_m, d.y_m) > options.localise_translation_m ||
         std::abs(d.yaw_rad) > options.localise_rotation_rad;
}

// The hypothesis takes a refinement's posture, what the rules said of it and its cost at `scan`.
// Its cost enters the evidence only at an evidence scan (Localiser::EvidenceDue).
void TakeRefinement(Hypothesis& h, const RankedCandidate& refined, std::size_t scan,
                    const LocalisationOptions& options, bool evidence) {
  h.T_world_robot = refined.T_world_robot;
  h.cost = refined.cost;
  h.verdict = refined.verdict;
  h.expect_value_m = refined.test.expect_value_m;
  h.match_ratio = refined.test.MatchRatio();
  h.truncated_mean_m = TruncatedMeanDistance(refined.test, options.scoring.test.match_threshold_m);
  if (evidence) RecordCost(h, scan, h.truncated_mean_m, h.expect_value_m, h.match_ratio);
}

// "(x, y, θ)" of a posture, for the reasons a hypothesis was discarded.
std::string Describe(const Pose2D& p) {
  char text[80];
  std::snprintf(text, sizeof text, "(%.2f, %.2f, %.3f)", p.x_m, p.y_m, p.yaw_rad);
  return text;
}

}  // namespace

WideSearchOptions LocaliserOptions::DefaultGlobalSearch() {
  WideSearchOptions search;
  // Coarser than the recovery's search (the refinement converges from a cell and a degree off):
  // 0.1 m cells, top blocks of 6.4 m, 1° headings: 0.2–0.7 s over ACES's 58 m × 58 m map
  // (docs/BENCHMARKS.md).
  search.field.resolution_m = 0.1;
  search.field.sigma_m = 0.15;
  search.field.levels = 7;
  search.min_heading_step_rad = M_PI / 180.0;
  search.max_candidates = 8;
  search.min_separation_m = 0.5;
  search.min_separation_rad = 0.2;
  search.max_beams = 100;
  return search;
}

void LocaliserOptions::Validate() const {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("LocaliserOptions: ") + what);
  };
  search.Validate();
  require(confirm_after >= 1, "confirm_after must be >= 1");
  require(std::isfinite(research_distance_m) && research_distance_m >= 0.0,
          "research_distance_m must be >= 0");
  require(std::isfinite(research_turn_rad) && research_turn_rad >= 0.0,
          "research_turn_rad must be >= 0");
  require(drop_after_unconfirmed >= 1, "drop_after_unconfirmed must be >= 1");
  require(lost_after_unconfirmed >= 1, "lost_after_unconfirmed must be >= 1");
  require(max_hypotheses >= 1, "max_hypotheses must be >= 1");
  require(std::isfinite(min_cost_excess_ratio) && min_cost_excess_ratio >= 0.0,
          "min_cost_excess_ratio must be >= 0");
  require(std::isfinite(same_posture_m) && same_posture_m >= 0.0, "same_posture_m must be >= 0");
  require(std::isfinite(same_posture_rad) && same_posture_rad >= 0.0,
          "same_posture_rad must be >= 0");
}

Localiser::Localiser(const LocaliserConfig& config, LaserMounting mounting, LineMap line_map,
                     PointMap point_map)
    : config_(config),
      mounting_(mounting),
      line_map_(std::move(line_map)),
      point_map_(std::move(point_map)) {
  config_.session.Validate();
  config_.localiser.Validate();
  config_.localisation.validation.Validate();
  if (View().empty())
    throw std::invalid_argument("localise: the map is empty, there is nothing to localise on");
  if (config_.initial_pose) {
    hypotheses_.emplace_back();
    hypotheses_.back().T_world_robot = *config_.initial_pose;
    hypotheses_.back().searches = 1;  // the user's word stands for a search
  }
}

IterationRecord Localiser::Process(const Iteration& given) {
  const auto start = std::chrono::steady_clock::now();
  std::optional<Iteration> replaced;
  bool frozen = false;
  const Iteration& iteration = UsableOdometry(given, replaced, frozen);
  IterationRecord record = BeginRecord(iteration, count_);
  record.odometry_frozen = frozen;
  in_force_ = BoundedOptions(record);
  if (iteration.odometry && last_odometry_) {
    const Pose2D increment = Between(*last_odometry_, *iteration.odometry);
    for (Hypothesis& h : hypotheses_) h.T_world_robot = h.T_world_robot * increment;
    if (last_output_) last_output_ = *last_output_ * increment;
  }
  if (!hypotheses_.empty()) {
    record.prediction = hypotheses_.front().T_world_robot;
    record.max_expect_value_m = BoundAt(record.prediction);
  }
  const bool search = SearchDue(iteration);
  evidence_ = EvidenceDue(iteration);
  const bool still_unconfirmed = !confirmed_ && config_.localiser.track_while_still;
  if (!hypotheses_.empty() && (search || still_unconfirmed ||
                               MovedSince(last_localised_odometry_, iteration, config_.session))) {
    Track(record, iteration);
  } else if (!search) {
    record.skipped = true;
  }
  if (search) Search(record, iteration);
  if (!record.skipped && iteration.odometry) last_localised_odometry_ = iteration.odometry;
  if (!record.skipped && evidence_) last_evidence_odometry_ = iteration.odometry;
  record.not_evidence = !record.skipped && !evidence_;
  record.without_odometry =
      odometry_from_scans_ && !record.skipped && record.localisation.has_value();
  record.odometry_from_scans = record.without_odometry && iteration.odometry.has_value();
  Prune(record);
  Conclude(record);
  if (search)
    last_search_output_ = record.posed ? std::optional<Pose2D>(record.T_world_robot) : std::nullopt;
  LearnMotion(record, iteration);
  if (iteration.odometry) last_odometry_ = iteration.odometry;
  ++count_;
  record.map_points = point_map_.live_size();
  record.total_s = SecondsSince(start);
  return record;
}

// `given`, or a copy in `replaced` whose odometry is the scans' own (ScanOdometry; none with
// localise.scan_odometry off) when the log's is missing, ignored, or frozen (`frozen` says so).
const Iteration& Localiser::UsableOdometry(const Iteration& given,
                                           std::optional<Iteration>& replaced, bool& frozen) {
  frozen = !config_.session.ignore_odometry && frozen_.SetAside(given);
  const bool from_scans = config_.session.ignore_odometry || frozen || !given.odometry;
  if (from_scans) {
    // Scans that had the log's odometry in between were not matched: the scan before is not the
    // last one the scans' odometry saw.
    if (!odometry_from_scans_) scan_odometry_.Reset();
    replaced = given;
    replaced->odometry.reset();
    if (config_.localiser.scan_odometry) replaced->odometry = scan_odometry_.Next(given.scan);
  }
  const Iteration& iteration = from_scans ? *replaced : given;
  if (from_scans != odometry_from_scans_) {
    // The other odometry's poses do not compare with this one's: no increment at this scan, and
    // the travel towards the next global search counts from here.
    last_odometry_.reset();
    last_localised_odometry_.reset();
    last_evidence_odometry_.reset();
    if (last_search_odometry_) last_search_odometry_ = iteration.odometry;
    odometry_from_scans_ = from_scans;
  }
  return iteration;
}

// Without odometry, the motion between consecutive confirmed postures sizes the motion search.
void Localiser::LearnMotion(const IterationRecord& record, const Iteration& iteration) {
  if (record.validated && last_confirmed_ &&
      SearchesMotion(iteration, count_, config_.session.motion_search))
    motion_.Add(Between(*last_confirmed_, record.T_world_robot));
  if (record.validated)
    last_confirmed_ = record.T_world_robot;
  else if (!record.skipped)
    last_confirmed_.reset();
}

// The whole map is searched when a confirmed posture was just lost and, until one is confirmed,
// each time the odometry moved or turned enough since the last search: a new view may show a
// place the last one missed, the same view would not. While no hypothesis is held that is the
// log's odometry or the scans' own; without either (the scans' match on the scan before failed)
// the view itself must have changed: ranges that moved as a session tells a frozen odometry.
bool Localiser::SearchDue(const Iteration& iteration) const {
  if (search_due_) return true;
  if (confirmed_ && !hypotheses_.empty()) return false;
  if (hypotheses_.empty() && !iteration.odometry) return ViewChanged(iteration.scan);
  // Without odometry the travel is the output posture's, since the one output at the last search.
  const std::optional<Pose2D>& from =
      iteration.odometry ? last_search_odometry_ : last_search_output_;
  if (!from) return true;
  const Pose2D since =
      Between(*from, iteration.odometry ? *iteration.odometry : hypotheses_.front().T_world_robot);
  const LocaliserOptions& o = config_.localiser;
  return std::hypot(since.x_m, since.y_m) >= o.research_distance_m ||
         std::abs(since.yaw_rad) >= o.research_turn_rad;
}

// Whether this scan's costs are evidence: a new view since the last scan whose costs were, by the
// session's insert gate (always without odometry, at the first, or with the option off).
bool Localiser::EvidenceDue(const Iteration& iteration) const {
  if (!config_.localiser.evidence_from_new_views || !iteration.odometry || !last_evidence_odometry_)
    return true;
  const Pose2D since = Between(*last_evidence_odometry_, *iteration.odometry);
  return std::hypot(since.x_m, since.y_m) >= config_.session.insert_translation_m ||
         std::abs(since.yaw_rad) >= config_.session.insert_rotation_rad;
}

// Whether `scan`'s ranges differ from those of the scan last searched by more than the frozen
// odometry's test allows a robot standing still (true when that cannot be told).
bool Localiser::ViewChanged(const LaserScan& scan) const {
  const double still_m = config_.session.motion_search.frozen_odometry_range_change_m;
  if (!last_search_scan_ || still_m <= 0.0) return true;
  const std::optional<double> change_m = MedianRangeChange(*last_search_scan_, scan);
  return !change_m || *change_m > still_m;
}

// The whole map searched; every refined candidate the rules validate becomes a hypothesis. The
// record keeps the search's candidates unless the held hypotheses were localised at this scan.
void Localiser::Search(IterationRecord& record, const Iteration& iteration) {
  const LaserScan& scan = iteration.scan;
  search_due_ = false;
  last_search_odometry_ = iteration.odometry;
  last_search_scan_ = scan;
  for (Hypothesis& h : hypotheses_) ++h.searches;
  record.search_window = WholeMapWindow(View());
  record.search =
      WideSearch(View(), scan, *record.search_window, config_.localiser.search, &search_field_);
  std::vector<Candidate> candidates;
  for (std::size_t i = 0; i < record.search->candidates.size(); ++i) {
    const Pose2D T_world_robot = mounting_.RobotPose(record.search->candidates[i].T_world_laser);
    candidates.push_back({T_world_robot, "search" + std::to_string(i), BoundAt(T_world_robot)});
  }
  if (candidates.empty()) {
    record.verdict = Verdict::kNoValidPairs;
    return;
  }
  LocalisationResult result =
      Localise(View(), scan, candidates, mounting_, in_force_, RefinePolicy::kAll);
  for (const RankedCandidate& refined : result.refined)
    if (refined.verdict == Verdict::kValid) {
      Hypothesis found;
      TakeRefinement(found, refined, count_, in_force_, evidence_);
      found.confirmed_in_row = found.confirmations = 1;
      found.validated = true;
      hypotheses_.push_back(found);
    }
  if (record.localisation) return;
  record.localisation = std::move(result);
  const RankedCandidate* kept = record.Kept();
  record.verdict = kept ? kept->verdict : Verdict::kNoValidPairs;
}

// Every hypothesis localised from its own prediction; rule 3 then judges them against each other
// (one far costlier than the best held is not validated). The record keeps the best one's.
void Localiser::Track(IterationRecord& record, const Iteration& iteration) {
  const bool turning = !iteration.odometry || !last_localised_odometry_ ||
                       std::abs(Between(*last_localised_odometry_, *iteration.odometry).yaw_rad) >
                           config_.session.heading_candidates_min_turn_rad;
  std::vector<LocalisationResult> results;
  for (Hypothesis& h : hypotheses_) {
    bool searched = false;
    results.push_back(LocaliseHypothesis(h, iteration, turning, searched));
    record.motion_searched_hypotheses += searched;
    h.verdict = Verdict::kNoValidPairs;
    if (const RankedCandidate* kept = results.back().Kept())
      TakeRefinement(h, *kept, count_, in_force_, evidence_);
    h.validated = results.back().validated();
  }
  const std::vector<bool> counts =
      JudgeRelativeCost(hypotheses_, config_.localisation.validation.max_cost_ratio,
                        config_.localiser.relative_cost_needs_truncated_mean);
  for (std::size_t i = 0; i < hypotheses_.size(); ++i) {
    if (counts[i])
      Count(hypotheses_[i]);
    else
      hypotheses_[i].confirmed_in_row = 0;  // not validated at this scan, but not a failure
  }
  std::vector<std::size_t> order(hypotheses_.size());
  std::iota(order.begin(), order.end(), 0);
  const std::size_t since = CommonSince(hypotheses_);
  std::stable_sort(order.begin(), order.end(), [&](std::size_t a, std::size_t b) {
    return RanksBefore(hypotheses_[a], hypotheses_[b], since);
  });
  record.localisation = std::move(results[order.front()]);
  const RankedCandidate* kept = record.Kept();
  record.verdict = kept ? kept->verdict : Verdict::kNoValidPairs;
  if (kept && !hypotheses_[order.front()].validated && kept->verdict == Verdict::kValid)
    record.verdict = Verdict::kHighCost;  // valid alone, but far costlier than another held
}

// One hypothesis localised from its own prediction; without odometry, searched for around it when
// the rules confirm nothing there or the refinement moved beyond the minima (NeedsMotionSearch).
LocalisationResult Localiser::LocaliseHypothesis(const Hypothesis& h, const Iteration& iteration,
                                                 bool turning, bool& searched) const {
  std::vector<Candidate> candidates =
      PredictionCandidates(h.T_world_robot, {}, turning, mounting_, config_.session);
  const double bound_m = BoundAt(h.T_world_robot);  // one place: one bound for all
  for (Candidate& c : candidates) c.max_expect_value_m = bound_m;
  auto localise = [&] {
    return Localise(View(), iteration.scan, candidates, mounting_, in_force_,
                    PredictionRefinePolicy(config_.session),
                    config_.session.max_refined_candidates);
  };
  LocalisationResult result = localise();
  searched = SearchesMotion(iteration, count_, config_.session.motion_search) &&
             NeedsMotionSearch(result, h.T_world_robot, config_.session.motion_search);
  if (!searched) return result;
  const RecoveryOptions& r = config_.session.recovery;
  const SearchWindow window = motion_.Window(mounting_.LaserPose(h.T_world_robot), r);
  const WideSearchResult search = WideSearch(View(), iteration.scan, window, r.search);
  for (std::size_t i = 0; i < search.candidates.size(); ++i)
    candidates.push_back({mounting_.RobotPose(search.candidates[i].T_world_laser),
                          "search" + std::to_string(i), bound_m});
  LocalisationResult again = localise();
  again.evaluate_s += result.evaluate_s;
  again.refine_s += result.refine_s;
  return again;
}

// Discards the hypotheses the rules stopped validating or another out-costed (the reasons go into
// `record`), merges the ones that met, keeps the best. A confirmed posture the rules stopped
// validating is lost: held on, unconfirmed, with a search.
void Localiser::Prune(IterationRecord& record) {
  const LocaliserOptions& o = config_.localiser;
  if (confirmed_ && !hypotheses_.empty() &&
      hypotheses_.front().unconfirmed_in_row >= o.lost_after_unconfirmed) {
    confirmed_ = false;
    lost_ = search_due_ = true;
    hypotheses_.front().held = true;
    hypotheses_.front().unconfirmed_in_row = 0;
    hypotheses_.front().confirmed_in_row = 0;
  }
  // Any hypothesis goes once another cost less at the same scans beyond chance (OutCosted). A
  // held posture that is no longer refined goes once another has been validated confirm_after
  // scans in a row: a stretch the map explains badly is not taken for a robot carried elsewhere.
  const bool competitor = std::any_of(hypotheses_.begin(), hypotheses_.end(), [&](const auto& h) {
    return !h.held && h.confirmed_in_row >= o.confirm_after;
  });
  const int patience = confirmed_ ? o.lost_after_unconfirmed : o.drop_after_unconfirmed;
  std::vector<Hypothesis> staying;
  for (const Hypothesis& h : hypotheses_) {
    std::string why = OutCosted(h);
    if (why.empty() && h.unconfirmed_in_row >= patience && (!h.held || (competitor && !Costed(h))))
      why = "not validated " + std::to_string(h.unconfirmed_in_row) +
            " scans in a row (last: " + ToString(h.verdict) + ")" +
            (h.held ? ", and another validated " + std::to_string(o.confirm_after) : "");
    if (why.empty())
      staying.push_back(h);
    else
      record.discarded.push_back(Describe(h.T_world_robot) + ": " + why);
  }
  hypotheses_ = std::move(staying);
  const std::size_t since = CommonSince(hypotheses_);
  std::stable_sort(
      hypotheses_.begin(), hypotheses_.end(),
      [&](const Hypothesis& a, const Hypothesis& b) { return RanksBefore(a, b, since); });
  std::vector<Hypothesis> kept;
  for (const Hypothesis& h : hypotheses_) {
    const bool seen = std::any_of(kept.begin(), kept.end(), [&](const Hypothesis& k) {
      const Pose2D d = Between(k.T_world_robot, h.T_world_robot);
      return std::hypot(d.x_m, d.y_m) < o.same_posture_m &&
             std::abs(d.yaw_rad) < o.same_posture_rad;
    });
    if (!seen && static_cast<int>(kept.size()) < o.max_hypotheses) kept.push_back(h);
  }
  hypotheses_ = std::move(kept);
}

// Whether `h` was refined at one of the last confirm_after scans (so it can be out-costed).
bool Localiser::Costed(const Hypothesis& h) const {
  const auto recent = static_cast<std::size_t>(config_.localiser.confirm_after);
  return !h.costs.empty() && h.costs.back().scan + recent >= count_;
}

// Rule 2's E_max for this scan: the laser signature learned from the confirmed posture's
// validated scans (as a session learns it), or the configured one; both go into `record`.
LocalisationOptions Localiser::BoundedOptions(IterationRecord& record) const {
  LocalisationOptions options = config_.localisation;
  record.signature_expect_value_m =
      signature_.ExpectValueBound(config_.localisation.validation.max_expect_value_m);
  if (config_.session.learned_max_expect_value)
    options.validation.max_expect_value_m = record.signature_expect_value_m;
  record.max_expect_value_m = options.validation.max_expect_value_m;
  return options;
}

// Rule 2's E_max at a posture: BoundedOptions' with the prior raised by the place's excess.
double Localiser::BoundAt(const Pose2D& T_world_robot) const {
  const double prior =
      config_.place_bound.At(T_world_robot, config_.localisation.validation.max_expect_value_m);
  return config_.session.learned_max_expect_value ? signature_.ExpectValueBound(prior) : prior;
}

// Why `h` goes: another held hypothesis cost less at the scans both were localised at, beyond
// chance, or outmatched it there (hypothesis_evidence.hpp); "" when none did.
std::string Localiser::OutCosted(const Hypothesis& h) const {
  const LocaliserOptions& o = config_.localiser;
  for (const Hypothesis& other : hypotheses_) {
    if (&other == &h) continue;
    // A truncated mean higher beyond chance decides nothing where h matched its pairs tighter
    // beyond chance (the expected value's test the other way): evidence both ways.
    const CostComparison c = CompareCosts(h, other, o.confirm_after, o.min_cost_excess_ratio);
    const CostComparison e =
        CompareSeries(h, other, &CostAt::expect_value_m, o.confirm_after, o.min_cost_excess_ratio);
    const bool costlier =
        c.decided &&
        !(o.drop_outmatched && MatchedTighter(h, other, o.confirm_after, o.min_cost_excess_ratio));
    if (!costlier && !(o.drop_outmatched && Outmatched(e, c))) continue;
    char text[200];
    if (!costlier) {
      std::snprintf(text, sizeof text,
                    "outmatched by %s at the last %d scans: expected value %.0f %% higher "
                    "(paired t %.1f), truncated mean higher too",
                    Describe(other.T_world_robot).c_str(), e.scans,
                    100.0 * e.mean_excess / e.cheaper_mean, e.t);
      return text;
    }
    std::snprintf(text, sizeof text,
                  "truncated mean distance %.0f %% more than %s at the last %d scans (paired t "
                  "%.1f)",
                  100.0 * c.mean_excess / c.cheaper_mean, Describe(other.T_world_robot).c_str(),
                  c.scans, c.t);
    return text;
  }
  return "";
}

// Which hypothesis is output (localise.steady_output): the best ranked, or while ambiguous the
// one followed at the scan before, unless it failed the rules here or another is clearly cheaper.
std::size_t Localiser::Output() const {
  const LocaliserOptions& o = config_.localiser;
  if (!o.steady_output || confirmed_ || hypotheses_.size() < 2 || !last_output_) return 0;
  return SteadyOutput(hypotheses_, *last_output_, o.same_posture_m, o.same_posture_rad,
                      o.min_cost_excess_ratio);
}

// The state after this scan, the posture (the output hypothesis), confirmation, loss and recovery.
void Localiser::Conclude(IterationRecord& record) {
  if (hypotheses_.empty()) {
    record.hypotheses.clear();
    record.state = "searching";
    record.posed = false;
    record.validated = false;
    record.lost = lost_;
    return;
  }
  // The output first, the others in their ranking.
  const auto output = hypotheses_.begin() + static_cast<std::ptrdiff_t>(Output());
  std::rotate(hypotheses_.begin(), output, output + 1);
  record.hypotheses = hypotheses_;
  const Hypothesis& best = hypotheses_.front();
  if (!confirmed_ && hypotheses_.size() == 1 && best.searches >= 1 &&
      best.confirmed_in_row >= config_.localiser.confirm_after) {
    confirmed_ = true;
    record.recovered = lost_;
    lost_ = false;
  }
  record.state = confirmed_ ? "confirmed" : hypotheses_.size() > 1 ? "ambiguous" : "tentative";
  record.T_world_robot = best.T_world_robot;
  last_output_ = best.T_world_robot;
  record.validated = confirmed_ && best.validated && !record.skipped;
  if (record.validated)
    if (const RankedCandidate* kept = record.Kept()) signature_.Add(kept->test);
  record.lost = lost_;
}

}  // namespace scanloc
