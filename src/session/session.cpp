#include "scanloc/session/session.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "scanloc/session/new_ground.hpp"
#include "scanloc/session/tighter_refinement.hpp"

namespace scanloc {
namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

bool MovedMoreThan(const Pose2D& from, const Pose2D& to, double translation_m,
                   double rotation_rad) {
  const Pose2D delta = Between(from, to);
  return std::hypot(delta.x_m, delta.y_m) > translation_m || std::abs(delta.yaw_rad) > rotation_rad;
}

// The odometry prediction (the first candidate) is disproved when its cost (3.11) exceeds
// cost_ratio times the kept refinement's.
bool PredictionDisproved(const LocalisationResult& result, double cost_ratio) {
  const RankedCandidate* kept = result.Kept();
  if (kept == nullptr || result.evaluated.empty()) return false;
  return result.evaluated.front().cost > cost_ratio * kept->cost;
}

}  // namespace

void MotionPriorOptions::Validate() const {
  if (!(floor_m > 0.0 && along_per_m >= 0.0 && across_per_m >= 0.0) ||
      !std::isfinite(floor_m + along_per_m + across_per_m))
    throw std::invalid_argument(
        "MotionPriorOptions: floor_m must be positive and the growths per metre >= 0");
}

void SessionOptions::Validate() const {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("SessionOptions: ") + what);
  };
  require(heading_spread_rad >= 0.0 && heading_spread_rad < M_PI, "heading_spread_rad in [0, π)");
  require(max_refined_candidates >= 1, "max_refined_candidates must be >= 1");
  require(heading_step_rad > 0.0, "heading_step_rad must be positive");
  require(heading_candidates_min_turn_rad >= 0.0, "heading_candidates_min_turn_rad must be >= 0");
  require(heading_spread_rad / heading_step_rad <= 100.0, "at most 100 heading steps per side");
  require(localise_translation_m >= 0.0 && localise_rotation_rad >= 0.0,
          "localise thresholds must be >= 0");
  require(extension.free_space_margin_m >= 0.0, "free_space_margin_m must be >= 0");
  require(extension.free_space_margin_per_m >= 0.0 && extension.free_space_margin_per_m < 1.0,
          "free_space_margin_per_m must be in [0, 1)");
  require(insert_translation_m >= 0.0 && insert_rotation_rad >= 0.0,
          "insert thresholds must be >= 0");
  signature.Validate();
  motion_prior.Validate();
  correction_gate.Validate();
  correction_drift.Validate();
  odometry_calibration.Validate();
  recovery.Validate();
  motion_search.Validate();
  loop_closure.Validate();
  require(std::isfinite(initial_pose.x_m) && std::isfinite(initial_pose.y_m) &&
              std::isfinite(initial_pose.yaw_rad),
          "initial_pose must be finite");
}

Session::Session(const SessionConfig& config, LaserMounting mounting, LineMap line_map,
                 PointMap point_map)
    : options_(config.session),
      localisation_(config.localisation),
      mounting_(mounting),
      line_map_(std::move(line_map)),
      point_map_(std::move(point_map)),
      signature_(options_.signature),
      drift_(options_.recovery),
      gate_(options_.correction_gate),
      correction_drift_(options_.correction_drift),
      loop_(options_.loop_closure, mounting_),
      motion_(options_.motion_search),
      frozen_(options_.motion_search.frozen_odometry_range_change_m),
      calibration_(options_.odometry_calibration) {
  options_.Validate();
  if (options_.loop_closure.enabled) loop_.SetPriorMap(point_map_);
  localisation_.validation.Validate();
  localisation_.scoring.test.Validate();
  localisation_.scoring.distance.Validate();
}

IterationRecord Session::Process(const Iteration& iteration) {
  return Step(iteration, nullptr);
}

IterationRecord Session::Replay(const Iteration& iteration, const RecordedIteration& recorded) {
  IterationRecord record = Step(iteration, &recorded);
  const std::string mismatch = DescribeReplayMismatch(record, recorded);
  if (!mismatch.empty()) throw ReplayMismatch(mismatch);
  return record;
}

IterationRecord Session::Step(const Iteration& given, const RecordedIteration* recorded) {
  const auto start = std::chrono::steady_clock::now();
  std::optional<Iteration> stripped, calibrated;
  bool frozen = false;
  const Iteration& usable = UsableOdometry(given, stripped, frozen);
  const Iteration& iteration = CalibratedOdometry(usable, calibrated);
  IterationRecord record = BeginRecord(iteration, count_);
  record.odometry_frozen = frozen;
  record.prediction = Predict(iteration);
  if (iteration.odometry && last_odometry_) {
    drift_.Moved(Between(*last_odometry_, *iteration.odometry));
    gate_.Moved(Between(*last_odometry_, *iteration.odometry));
  }
  if (View().empty() && iteration.external_candidates.empty()) {
    // Nothing to localise against: the posture is the prediction (the origin at first, §3.2.2).
    record.first = count_ == 0;
    record.T_world_robot = record.prediction;
    record.validated = record.first;
    record.verdict = record.first ? Verdict::kValid : Verdict::kNoValidPairs;
  } else if (!ShouldLocalise(iteration)) {
    record.skipped = true;
    record.T_world_robot = record.prediction;
  } else if (recorded) {
    RestoreLocalised(record, iteration, *recorded);
  } else {
    LocaliseInto(record, iteration);
  }
  record.without_odometry = !record.skipped && !record.first && !iteration.odometry;
  record.new_ground = recorded ? recorded->new_ground : OnNewGround(record, iteration.scan);
  MaybeExtend(record, iteration.scan);
  if (count_ == 0 && iteration.odometry) last_localised_odometry_ = *iteration.odometry;
  last_pose_ = record.T_world_robot;
  std::optional<Eigen::Matrix3d> covariance;
  if (recorded) {
    covariance = recorded->kept_covariance;
  } else if (const RankedCandidate* kept = record.Kept();
             kept && kept->refinement && kept->refinement->has_covariance) {
    covariance = kept->refinement->covariance;
  }
  MaybeCloseLoop(record, iteration, covariance);
  LearnCalibration(record, usable.odometry);
  if (iteration.odometry) last_odometry_ = iteration.odometry;
  ++count_;
  record.map_points = point_map_.live_size();
  record.total_s = SecondsSince(start);
  return record;
}

const Iteration& Session::UsableOdometry(const Iteration& given, std::optional<Iteration>& stripped,
                                         bool& frozen) {
  frozen = !options_.ignore_odometry && frozen_.SetAside(given);
  return WithoutOdometryIf(options_.ignore_odometry || frozen, given, stripped);
}

// The log's odometry steps, scaled by the calibration, integrated from its first pose. Until a
// scale is applied the log's odometry is passed on as it is.
const Iteration& Session::CalibratedOdometry(const Iteration& usable,
                                             std::optional<Iteration>& calibrated) {
  if (!options_.odometry_calibration.enabled || !usable.odometry) return usable;
  const Pose2D raw = *usable.odometry;
  calibrated_apart_ =
      calibrated_apart_ || calibration_.distance().value != 1.0 || calibration_.turn().value != 1.0;
  calibrated_odometry_ =
      calibrated_apart_ && raw_odometry_
          ? calibrated_odometry_ * calibration_.Calibrated(Between(*raw_odometry_, raw))
          : raw;
  raw_odometry_ = raw;
  if (!calibrated_apart_) return usable;
  calibrated.emplace(usable);
  calibrated->odometry = calibrated_odometry_;
  return *calibrated;
}

// A confirmed scan teaches the calibration the step from an earlier confirmed one (at least
// min_step_m or min_step_rad of the log's odometry back), when every scan between was confirmed or
// passed over (not localised) and nothing moved the session: the log's odometry over that step
// against the session's. A scan localised without confirmation, searched for, or whose correction
// a check refused ends the step.
void Session::LearnCalibration(const IterationRecord& record, const std::optional<Pose2D>& raw) {
  if (!options_.odometry_calibration.enabled || record.skipped) return;
  const bool confirmed = record.validated && raw && !record.slide_refused &&
                         !record.beyond_odometry && !record.search && !record.recovered;
  if (!confirmed) {
    calibration_anchor_.reset();
    return;
  }
  if (calibration_anchor_ && !record.first &&
      calibration_.Learn(Between(calibration_anchor_->odometry, *raw),
                         Between(calibration_anchor_->posture, record.T_world_robot)))
    calibration_anchor_.reset();
  if (!SamePosture(last_pose_, record.T_world_robot))
    calibration_anchor_.reset();
  else if (!calibration_anchor_)
    calibration_anchor_ = CalibrationAnchor{*raw, record.T_world_robot};
}

MapView Session::View() const {
  return {line_map_.empty() ? nullptr : &line_map_, &point_map_};
}

// The previous posture moved by the odometry increment (the initial posture at first).
Pose2D Session::Predict(const Iteration& iteration) const {
  if (count_ == 0) return options_.initial_pose;
  if (iteration.odometry && last_odometry_)
    return last_pose_ * Between(*last_odometry_, *iteration.odometry);
  return last_pose_;
}

// External candidates are always tried; otherwise the robot must have moved since the last
// localised scan (without odometry, every scan is localised).
bool Session::ShouldLocalise(const Iteration& iteration) const {
  return !iteration.external_candidates.empty() || count_ == 0 || !iteration.odometry ||
         MovedMoreThan(last_localised_odometry_, *iteration.odometry,
                       options_.localise_translation_m, options_.localise_rotation_rad);
}

std::vector<Candidate> PredictionCandidates(const Pose2D& prediction,
                                            const std::vector<Pose2D>& external, bool turning,
                                            const LaserMounting& mounting,
                                            const SessionOptions& options) {
  std::vector<Candidate> candidates{{prediction, "odometry"}};
  const int steps = !turning ? 0
                             : static_cast<int>(std::floor(
                                   options.heading_spread_rad / options.heading_step_rad + 1e-3));
  for (int s = 1; s <= steps; ++s)
    for (const int sign : {-1, 1}) {
      const double offset = sign * s * options.heading_step_rad;
      // Turned about the laser, so that all share its position (and one simulated sweep).
      Pose2D turned = mounting.LaserPose(prediction);
      turned.yaw_rad = NormalizeAngle(turned.yaw_rad + offset);
      char label[32];
      std::snprintf(label, sizeof label, "odometry%+.0fdeg", offset * 180.0 / M_PI);
      candidates.push_back({mounting.RobotPose(turned), label});
    }
  for (std::size_t i = 0; i < external.size(); ++i)
    candidates.push_back({external[i], "external" + std::to_string(i)});
  return candidates;
}

RefinePolicy PredictionRefinePolicy(const SessionOptions& options) {
  return options.refine_prediction ? RefinePolicy::kBestValidAndFirst : RefinePolicy::kBestValid;
}

// The heading candidates only when the odometry turned since the last localised scan (or is
// unknown).
bool Session::Turning(const Iteration& iteration) const {
  return !iteration.odometry ||
         std::abs(Between(last_localised_odometry_, *iteration.odometry).yaw_rad) >
             options_.heading_candidates_min_turn_rad;
}

// Localises the scan from the prediction's candidates, then `search`'s. With
// heading_candidates_on_failure, the turned candidates join only when none of the others passes
// the rules; the first round is then not refined, and its evaluation time is counted.
LocalisationResult Session::LocaliseCandidates(const Pose2D& prediction, const Iteration& iteration,
                                               const std::vector<Candidate>& search,
                                               const LocalisationOptions& options) const {
  const auto candidates = [&](bool turning) {
    std::vector<Candidate> all = PredictionCandidates(prediction, iteration.external_candidates,
                                                      turning, mounting_, options_);
    all.insert(all.end(), search.begin(), search.end());
    return all;
  };
  const bool turning = Turning(iteration);
  double first_round_s = 0.0;
  if (turning && options_.heading_candidates_on_failure) {
    LocalisationResult first =
        Localise(View(), iteration.scan, candidates(false), mounting_, options,
                 RefinePolicy::kValidOnly, options_.max_refined_candidates);
    if (first.best_evaluated >= 0) return first;
    first_round_s = first.evaluate_s;
  }
  LocalisationResult result =
      Localise(View(), iteration.scan, candidates(turning), mounting_, options,
               PredictionRefinePolicy(options_), options_.max_refined_candidates);
  result.evaluate_s += first_round_s;
  return result;
}

// Localise from the candidates (with the wide search's when lost), rule 2's E_max from the laser
// signature when so configured. A confirmed refinement is the posture and teaches the signature
// and the correction gate; one the gate refuses (far beyond the odometry's learned error, on
// little overlap) is neither confirmed nor kept; an unconfirmed one is flagged, and the posture
// may stay the prediction (TakesPrediction).
void Session::LocaliseInto(IterationRecord& record, const Iteration& iteration) {
  LocalisationOptions options = BoundedOptions(record);
  AddMotionPrior(options, record.prediction, iteration);
  std::vector<Candidate> search;
  const bool was_lost = drift_.lost();
  const bool searches_motion = SearchesMotion(iteration, count_, options_.motion_search);
  if (was_lost) AddSearchCandidates(record, iteration.scan, search);
  record.localisation = LocaliseCandidates(record.prediction, iteration, search, options);
  // Without odometry the map is searched when the last posture's candidates found nothing the
  // rules confirm, or only by moving farther than the search's minima (a dense log's scans
  // rarely need it, a sparse log's, 0.6–1 m apart, always do).
  if (searches_motion && !was_lost &&
      NeedsMotionSearch(*record.localisation, record.prediction, options_.motion_search)) {
    MotionSearchWindow(record);
    Search(record, iteration.scan, search);
    const LocalisationResult first = std::move(*record.localisation);
    record.localisation = LocaliseCandidates(record.prediction, iteration, search, options);
    record.localisation->evaluate_s += first.evaluate_s;
    record.localisation->refine_s += first.refine_s;
  }
  if (options_.keep_tighter_refinement)
    record.outranked_refinement =
        KeepTighterRefinement(*record.localisation, localisation_.scoring.test.match_threshold_m,
                              options_.correction_gate.overlap_fraction);
  const RankedCandidate& kept = *record.Kept();
  record.verdict = kept.verdict;
  record.validated = record.localisation->validated();
  // The wide search's window, not the gate, bounds a lost session's correction (and a scan
  // without odometry has no odometry to be beyond).
  if (!was_lost && !searches_motion) JudgeCorrection(record, kept);
  // Without odometry the prediction is only the last posture: nothing the scan could not
  // disprove.
  record.T_world_robot =
      !searches_motion && TakesPrediction(record, kept) ? record.prediction : kept.T_world_robot;
  if (!was_lost && !searches_motion) KeepDrift(record);
  if (record.validated) {
    signature_.Add(kept.test);
    if (!searches_motion && !record.slide_refused)
      gate_.Add(Between(record.prediction, record.T_world_robot), kept.test.MatchRatio());
  }
  AfterLocalised(record, iteration, was_lost);
}

// The correction gate and the slide check judge the kept refinement's correction of the
// prediction. A slide is a correction the scan does not demand: one the check refuses is refused
// only when the prediction as given passed the rules too, at a cost (3.11) within
// prediction_disproved_cost_ratio of the refinement's. The scan is then confirmed at the
// prediction, and the map goes on growing along the odometry; where the map disproves the
// prediction, the correction stands (an odometry gone wrong).
void Session::JudgeCorrection(IterationRecord& record, const RankedCandidate& kept) {
  record.correction_bound = gate_.Bound(drift_.unconfirmed());
  RefinementSupport support{kept.test.MatchRatio(), std::nullopt, true};
  if (kept.refinement && kept.refinement->has_covariance)
    support.position_covariance = kept.refinement->covariance.topLeftCorner<2, 2>();
  if (kept.refinement) support.converged = kept.refinement->converged;
  support.validated = record.validated;
  record.beyond_odometry =
      gate_.Refuses(record.prediction, kept.T_world_robot, support, drift_.unconfirmed());
  if (record.beyond_odometry) record.validated = false;
  correction_drift_.Predicted(record.prediction);
  if (record.validated)
    record.slide_check = correction_drift_.Check(
        kept.T_world_robot.Translation() - record.prediction.Translation(),
        record.correction_bound ? record.correction_bound->translation_m : 0.0);
  // Before the slide check has learned its bound, the refinement's own evidence of a slide.
  const bool learning = options_.correction_drift.window_m > 0.0 && !record.slide_check;
  const bool slides = record.slide_check
                          ? record.slide_check->Refused()
                          : learning && record.validated &&
                                gate_.Slides(record.prediction, kept.T_world_robot, support);
  record.slide_refused =
      slides && record.localisation->evaluated.front().verdict == Verdict::kValid &&
      !PredictionDisproved(*record.localisation, options_.prediction_disproved_cost_ratio);
}

// The localisation as recorded: its posture and verdict, the kept refinement's test taught to the
// signature when it was confirmed. The wide search is not run again (its window is).
void Session::RestoreLocalised(IterationRecord& record, const Iteration& iteration,
                               const RecordedIteration& recorded) {
  if (!recorded.localised)
    throw ReplayMismatch("the replay localises the scan, the record says it was not localised");
  BoundedOptions(record);
  const bool was_lost = drift_.lost();
  const bool searches_motion = SearchesMotion(iteration, count_, options_.motion_search);
  record.beyond_odometry = recorded.refused.has_value();
  record.slide_refused = recorded.slide_refused.has_value();
  if (!was_lost && !searches_motion) {
    record.correction_bound = gate_.Bound(drift_.unconfirmed());
    gate_.Restore(recorded.refused);
    correction_drift_.Predicted(record.prediction);
  }
  if (was_lost) {
    record.search_window = drift_.Window(mounting_.LaserPose(record.prediction));
    record.search.emplace();
  } else if (searches_motion && recorded.searched) {
    MotionSearchWindow(record);
    record.search.emplace();
  }
  record.localisation.emplace();
  record.verdict = recorded.verdict;
  record.validated = recorded.validated;
  record.outranked_refinement = recorded.outranked_refinement;
  // A withdrawn correction is restored as the tracker made it: the closure disputes it again.
  record.T_world_robot = recorded.disputed ? *recorded.disputed : recorded.T_world_robot;
  if (!was_lost && !searches_motion) KeepDrift(record);
  if (record.validated) {
    if (!recorded.kept_test)
      throw ReplayMismatch("the record is confirmed but holds no Likelihood Test of its posture");
    signature_.Add(*recorded.kept_test);
    if (!searches_motion && !record.slide_refused)
      gate_.Add(Between(record.prediction, record.T_world_robot), recorded.kept_test->MatchRatio());
  }
  AfterLocalised(record, iteration, was_lost);
}

// The posture the tracker kept, and its correction of the prediction when it was confirmed; a
// correction the slide check refused holds the check's window where it stands.
void Session::KeepDrift(const IterationRecord& record) {
  correction_drift_.Kept(record.T_world_robot,
                         record.validated
                             ? std::optional<Eigen::Vector2d>(record.T_world_robot.Translation() -
                                                              record.prediction.Translation())
                             : std::nullopt,
                         record.slide_refused);
}

// A scan keeps the prediction when the slide check refused its confirmed correction. An
// unconfirmed scan keeps it when the correction gate refused its correction, when its refinement
// had too little of the scan on the map to say anything (rule 1, or no valid pair), or, with
// unconfirmed_takes_prediction, unless the data disproves the prediction.
bool Session::TakesPrediction(const IterationRecord& record, const RankedCandidate& kept) const {
  if (record.slide_refused) return true;
  if (record.validated) return false;
  if (record.beyond_odometry) return true;
  if (options_.low_overlap_takes_prediction &&
      (kept.verdict == Verdict::kLowMatchRatio || kept.verdict == Verdict::kNoValidPairs))
    return true;
  if (options_.relative_low_overlap_takes_prediction && gate_.LowOverlap(kept.test.MatchRatio()))
    return true;
  return options_.unconfirmed_takes_prediction &&
         !PredictionDisproved(*record.localisation, options_.prediction_disproved_cost_ratio);
}

LocalisationOptions Session::BoundedOptions(IterationRecord& record) const {
  const LocalisationOptions options = SignatureBoundedOptions();
  record.signature_expect_value_m =
      signature_.ExpectValueBound(localisation_.validation.max_expect_value_m);
  record.max_expect_value_m = options.validation.max_expect_value_m;
  return options;
}

// The localisation's options, rule 2's E_max the laser signature's bound when it is to be.
LocalisationOptions Session::SignatureBoundedOptions() const {
  LocalisationOptions options = localisation_;
  if (options_.learned_max_expect_value)
    options.validation.max_expect_value_m =
        signature_.ExpectValueBound(localisation_.validation.max_expect_value_m);
  return options;
}

void Session::AddMotionPrior(LocalisationOptions& options, const Pose2D& prediction,
                             const Iteration& iteration) const {
  const MotionPriorOptions& prior = options_.motion_prior;
  if (!prior.enabled || !iteration.odometry || count_ == 0) return;
  const Pose2D step = Between(last_localised_odometry_, *iteration.odometry);
  const double moved_m = std::hypot(step.x_m, step.y_m);
  options.refiner.ceres.prior =
      PosturePrior{mounting_.LaserPose(prediction),
                   Eigen::Vector3d(1.0 / (prior.floor_m + prior.along_per_m * moved_m),
                                   1.0 / (prior.floor_m + prior.across_per_m * moved_m), 0.0)};
}

void Session::AfterLocalised(IterationRecord& record, const Iteration& iteration, bool was_lost) {
  drift_.Localised(record.validated);
  record.lost = drift_.lost();
  record.recovered = was_lost && record.validated;
  if (record.recovered) correction_drift_.Restart(record.T_world_robot);
  if (iteration.odometry) last_localised_odometry_ = *iteration.odometry;
  if (record.validated && SearchesMotion(iteration, count_, options_.motion_search))
    motion_.Add(Between(last_pose_, record.T_world_robot));
}

// The wide search's best postures over the window the odometry's drift may have left since the
// last confirmed scan (labels "search0", …).
void Session::AddSearchCandidates(IterationRecord& record, const LaserScan& scan,
                                  std::vector<Candidate>& candidates) const {
  record.search_window = drift_.Window(mounting_.LaserPose(record.prediction));
  Search(record, scan, candidates);
}

// Around the last posture, over the motion seen lately (at first, the recovery's initial window).
void Session::MotionSearchWindow(IterationRecord& record) const {
  record.search_window = motion_.Window(mounting_.LaserPose(record.prediction), options_.recovery);
  record.motion_search = true;
}

void Session::Search(IterationRecord& record, const LaserScan& scan,
                     std::vector<Candidate>& candidates) const {
  record.search = WideSearch(View(), scan, *record.search_window, options_.recovery.search);
  for (std::size_t i = 0; i < record.search->candidates.size(); ++i)
    candidates.push_back({mounting_.RobotPose(record.search->candidates[i].T_world_laser),
                          "search" + std::to_string(i)});
}

// An unconfirmed scan that kept the prediction where the map covers too little of it to judge it
// (new_ground.hpp), the session not lost.
bool Session::OnNewGround(const IterationRecord& record, const LaserScan& scan) const {
  const RankedCandidate* kept = record.Kept();
  if (!options_.map_new_ground || record.validated || record.skipped || record.lost || !kept ||
      record.localisation->evaluated.empty() ||
      (kept->verdict != Verdict::kLowMatchRatio && kept->verdict != Verdict::kNoValidPairs) ||
      !(record.T_world_robot.Translation() == record.prediction.Translation()))
    return false;
  return CoversTooLittle(record.localisation->evaluated.front().test, scan.CountValid(),
                         localisation_.validation.min_match_ratio);
}

// A validated scan, one on new ground (or any localised one, with insert_unvalidated) extends the
// map once the robot moved far enough from where the last one did.
void Session::MaybeExtend(IterationRecord& record, const LaserScan& scan) {
  const bool may_insert =
      record.validated || record.new_ground || (options_.insert_unvalidated && !record.skipped);
  if (!may_insert || (last_inserted_pose_ &&
                      !MovedMoreThan(*last_inserted_pose_, record.T_world_robot,
                                     options_.insert_translation_m, options_.insert_rotation_rad)))
    return;
  const auto start = std::chrono::steady_clock::now();
  record.carved =
      ExtendMap(point_map_, scan, mounting_.LaserPose(record.T_world_robot), options_.extension);
  last_inserted_pose_ = record.T_world_robot;
  record.inserted = true;
  if (record.validated) laid_.Add(record.index, scan, record.T_world_robot);
  record.insert_s = SecondsSince(start);
}

// With loop closure on, a scan that extended the map becomes a node, every scan is anchored to
// the newest node, and a closure is tried when one is due. After an accepted one that moved a node
// more than render_min_shift_m, the session goes on from the corrected node, on the map rendered
// again from every node.
void Session::MaybeCloseLoop(IterationRecord& record, const Iteration& iteration,
                             const std::optional<Eigen::Matrix3d>& covariance) {
  if (!options_.loop_closure.enabled) return;
  if (record.inserted)
    loop_.AddNode(record.index, iteration.scan, record.T_world_robot, covariance,
                  iteration.odometry);
  loop_.Anchor(record.index, record.T_world_robot, record.validated || record.skipped,
               iteration.odometry,
               AnchorTiming{record.timestamp_s, record.skipped, record.prediction});
  if (!record.inserted) return;
  record.closure = loop_.MaybeClose(localisation_, point_map_.options());
  if (WithdrawDisputedTurn(record)) return;
  if (!record.closure || !record.closure->rendered) {
    const LoopClosureOptions& o = options_.loop_closure;
    if (Tracking() && loop_.FirstNewestNode(2.0 * o.tracking_path_m,
                                            2 * static_cast<std::size_t>(o.tracking_min_nodes)) >
                          tracked_from_node_)
      RenderTracked();
    return;
  }
  // The map and the session follow the corrected nodes together; a smaller correction leaves
  // both where they were (the next node's edge takes up the difference).
  RenderTracked();
  last_pose_ = *loop_.NewestNode();
  last_inserted_pose_ = last_pose_;
  correction_drift_.Moved(last_pose_);
}

// A heading correction the closure tried at the same scan disputes is withdrawn: the node, the map
// tracked and the session go on from the prediction (turn_dispute.hpp).
bool Session::WithdrawDisputedTurn(IterationRecord& record) {
  const double fraction = options_.loop_closure.dispute_turn_of_bound;
  if (fraction <= 0.0 || !record.closure || !record.correction_bound) return false;
  record.turn_dispute = DisputedTurn(record.prediction, record.T_world_robot, *record.closure,
                                     fraction * record.correction_bound->rotation_rad,
                                     options_.loop_closure.agree_rad);
  if (!record.turn_dispute) return false;
  loop_.MoveNewestNode(record.prediction);
  record.T_world_robot = record.prediction;
  last_pose_ = record.prediction;
  last_inserted_pose_ = last_pose_;
  correction_drift_.Moved(last_pose_);
  RenderTracked();
  return true;
}

bool Session::Tracking() const {
  return options_.loop_closure.enabled && options_.loop_closure.tracking_path_m > 0.0;
}

// The map rendered again from the nodes: all of them, or the newest when tracking.
void Session::RenderTracked() {
  const LoopClosureOptions& o = options_.loop_closure;
  tracked_from_node_ =
      Tracking()
          ? loop_.FirstNewestNode(o.tracking_path_m, static_cast<std::size_t>(o.tracking_min_nodes))
          : 0;
  point_map_ = loop_.Render(point_map_.options(), options_.extension, tracked_from_node_);
}

// Closures that joined the graph unsolved are solved; the map is rendered from every node when
// tracking kept only the newest, when that solve moved a node, or to be carved by earlier scans.
void Session::Finish() {
  if (options_.loop_closure.enabled) {
    const bool moved = loop_.Finish();
    if (options_.loop_closure.final_match.enabled)
      MatchOnFinalMap();
    else if (Tracking() || moved || options_.extension.carve_with_earlier_scans)
      point_map_ = loop_.Render(point_map_.options(), options_.extension, 0, true);
  }
  if (!point_map_.empty())
    map_signature_ = MeasureMapSignature(View(), laid_, CorrectedPostures(), mounting_,
                                         localisation_, options_.signature);
}

// The final map matching: the nodes matched on the map rendered from every node, with the rules'
// E_max the laser signature learned; then the map kept is rendered from the postures it left.
// (The map matched on is carved as the map kept is: without the carving, the ghosts of moved
// doors and passers-by cost Fr079 0.0396 -> 0.0405 m and Intel's worst relation 0.15 -> 0.30 m.)
void Session::MatchOnFinalMap() {
  point_map_ = loop_.Render(point_map_.options(), options_.extension, 0, true);
  if (point_map_.empty()) return;
  final_match_ = loop_.MatchOnFinalMap(View(), SignatureBoundedOptions());
  if (final_match_->largest_shift_m > 0.0)
    point_map_ = loop_.Render(point_map_.options(), options_.extension, 0, true);
}

std::vector<std::optional<Pose2D>> Session::CorrectedPostures() const {
  if (!options_.loop_closure.enabled) return {};
  return loop_.CorrectedPostures();
}

const PoseGraph* Session::pose_graph() const {
  return options_.loop_closure.enabled ? &loop_.graph() : nullptr;
}

const OdometryCalibration* Session::odometry_calibration() const {
  return options_.odometry_calibration.enabled ? &calibration_ : nullptr;
}

const OdometryModel* Session::odometry_model() const {
  return options_.loop_closure.enabled ? &loop_.odometry_model() : nullptr;
}

}  // namespace scanloc
