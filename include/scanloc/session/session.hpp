#pragma once
// A localisation and mapping session, the chapter's loop: each iteration's posture is predicted
// from the odometry, gated (a robot that has not moved is not localised again), localised against
// the map built so far from candidates across the heading uncertainty (Localise), decided, and a
// validated scan extends the point map (ExtendMap, (3.6)).

#include <cmath>
#include <memory>
#include <optional>
#include <vector>

#include "scanloc/likelihood/candidate_ranking.hpp"
#include "scanloc/likelihood/laser_signature.hpp"
#include "scanloc/maps/line_map.hpp"
#include "scanloc/maps/point_map.hpp"
#include "scanloc/session/correction_drift.hpp"
#include "scanloc/session/correction_gate.hpp"
#include "scanloc/session/iteration.hpp"
#include "scanloc/session/localisation.hpp"
#include "scanloc/session/loop_closure.hpp"
#include "scanloc/session/map_extension.hpp"
#include "scanloc/session/map_signature.hpp"
#include "scanloc/session/motion_search.hpp"
#include "scanloc/session/odometry_calibration.hpp"
#include "scanloc/session/recovery.hpp"
#include "scanloc/session/scan_processor.hpp"

namespace scanloc {

// The odometry's prediction as a prior on the refinement (PosturePrior), translation only: σ =
// floor_m + per_m · the distance the odometry moved since the last localised scan, along the
// motion and across it. Where the scan leaves the posture free (a corridor's axis) the refinement
// keeps the odometry's position instead of wandering on noise. No prior on the heading: in fast
// turns the odometry's heading slips by degrees, and a prior there held it (docs/BENCHMARKS.md).
struct MotionPriorOptions {
  bool enabled = false;
  double floor_m = 0.02;
  double along_per_m = 0.1;
  double across_per_m = 0.05;
  void Validate() const;
};

struct SessionOptions {
  // Candidates: the odometry prediction turned by every multiple of heading_step_rad up to
  // ±heading_spread_rad (in fast in-place turns the odometry heading is off by 3–6° per scan).
  double heading_spread_rad = M_PI / 18.0;  // 10°
  double heading_step_rad = M_PI / 36.0;    // 5°
  // The turned candidates are tried only when the odometry turned more than this since the last
  // localised scan (the heading slips in turns); otherwise the prediction alone is tested.
  double heading_candidates_min_turn_rad = 0.0;
  // With this, the turned candidates are tried only when none of the others (the prediction, the
  // external and the wide search's candidates) passes the rules.
  bool heading_candidates_on_failure = false;
  // The candidates the rules left valid are refined, best first, up to this many; the refined
  // postures are tested again and ranked by the rules (the chapter's refine-then-validate): in
  // fast turns two headings 5° apart may both look plausible until they are refined.
  int max_refined_candidates = 3;
  // The prediction is refined too when the rules rejected it as given: a prediction a few
  // centimetres off may fail rule 2 where a turned candidate passes and refines to a wrong heading
  // (orebro, acapulco). Its refinement is kept only when the rules pass it and rank it first; when
  // no refinement passes, the flagged guess is the one the candidates the rules passed (or the
  // cheapest) give, as without it. Measured on all eight public logs (docs/BENCHMARKS.md,
  // "The prediction refined when the rules reject it as given").
  bool refine_prediction = true;
  // A scan is localised only when the odometry moved more than this since the last localised
  // one; the others get the odometry prediction (their posture is still recorded).
  double localise_translation_m = 0.05;
  double localise_rotation_rad = 0.035;
  // A validated scan extends the map when the robot moved more than this since the last one that
  // did (metres, radians).
  double insert_translation_m = 0.1;
  double insert_rotation_rad = 0.087;
  // Before a scan extends the map, its beams carve the free space they crossed. Chosen on the
  // robustness harness (docs/BENCHMARKS.md): 0.1 m + 1 % carves the double walls that a fixed
  // 0.2 m kept.
  MapExtensionOptions extension;
  bool insert_unvalidated =
      false;  // let non-validated scans extend the map (off: they are flagged)
  // An unconfirmed scan that kept the prediction where the map covers too little of it to judge it
  // (new_ground.hpp) extends the map at the prediction, unless the session is lost.
  bool map_new_ground = true;
  // A scan the rules do not confirm keeps the odometry prediction from the last posture rather
  // than its unconfirmed refinement: the session is never worse than the odometry it cannot
  // disprove.
  bool unconfirmed_takes_prediction = false;
  // ... unless the data disproves the prediction: its cost (3.11) exceeds this many times the kept
  // refinement's (in a turn where the odometry heading slipped, the refinement is the better
  // guess).
  double prediction_disproved_cost_ratio = 1.5;
  // Whatever unconfirmed_takes_prediction says, a scan whose kept refinement fails rule 1 (or has
  // no valid pair) keeps the prediction: with so little of the scan on the map nothing anchored
  // the refinement (after a gap in a log it wanders half a metre on a few beams), and the data
  // cannot disprove the odometry. Measured on all eight public logs under perturbations of the
  // defaults (docs/BENCHMARKS.md, "Never lost").
  bool low_overlap_takes_prediction = true;
  // ... and so does one whose kept refinement matches less of the scan than the correction gate's
  // overlap fraction (0.75) of the recent confirmed scans' median match ratio: rule 1's 30 % is
  // absolute, and a sparse log's unconfirmed refinements on 30–47 % of their pairs were 0.09–0.14 m
  // and up to 0.18 rad off where the prediction was within 1 cm (fhw noisy, scans 59–62). Measured
  // on all eight public logs (docs/BENCHMARKS.md, "Unconfirmed scans on less overlap than usual").
  bool relative_low_overlap_takes_prediction = true;
  // Among the valid refinements, one at a lower truncated mean distance is kept instead of the
  // rules' best when the best matched fewer pairs than correction_gate.overlap_fraction of its
  // (tighter_refinement.hpp; docs/BENCHMARKS.md, "A refinement that matched more, at a lower
  // truncated mean").
  bool keep_tighter_refinement = true;
  // The laser signature learned from the confirmed scans; with learned_max_expect_value, rule 2's
  // E_max is its bound (validation.max_expect_value_m the prior), otherwise it is only recorded.
  // On by default: the sparse Radish logs' scans lie 0.10–0.16 m (median EV) from a map laid by
  // their true poses, beyond the prior's 0.1 m, and the session stopped confirming anything.
  LaserSignatureOptions signature;
  bool learned_max_expect_value = true;
  // Off by default: it makes the sparse logs' scan-to-scan steps more accurate but does not keep
  // them from being lost (docs/BENCHMARKS.md, "A motion prior on the refinement").
  MotionPriorOptions motion_prior;
  // Refinements that move the posture much further from the prediction than the recent confirmed
  // scans' refinements did are refused (correction_gate.hpp).
  CorrectionGateOptions correction_gate;
  // Confirmed corrections that would add up to a slide over the last stretch of path are refused
  // (correction_drift.hpp).
  CorrectionDriftOptions correction_drift;
  // The odometry's distance and turn scales, learned from the confirmed steps and reported; with
  // apply, the odometry is scaled by them before anything uses it (odometry_calibration.hpp).
  OdometryCalibrationOptions odometry_calibration;
  // When the session counts itself lost, and the wide search it then adds.
  RecoveryOptions recovery;
  // The log's odometry is not used: every scan is localised as in a log without odometry
  // (motion_search), for odometry the user knows to be wrong.
  bool ignore_odometry = false;
  // Scans without odometry, searched for over the motion seen lately (motion_search.hpp).
  MotionSearchOptions motion_search;
  // Nodes, closures and the pose graph whose corrections move the map.
  LoopClosureOptions loop_closure;
  Pose2D initial_pose;  // T_world_robot of the first iteration (§3.2.2: by convention)
  void Validate() const;
};

// The candidates a session tries: the prediction, turned about the laser by every multiple of
// options.heading_step_rad up to ±options.heading_spread_rad when `turning`, then the external
// ones (labels "odometry", "odometry+5deg", …, "external0", …).
std::vector<Candidate> PredictionCandidates(const Pose2D& prediction,
                                            const std::vector<Pose2D>& external, bool turning,
                                            const LaserMounting& mounting,
                                            const SessionOptions& options);

// How the candidates of PredictionCandidates are refined: the valid ones best first (up to
// options.max_refined_candidates), and with options.refine_prediction the prediction as well.
RefinePolicy PredictionRefinePolicy(const SessionOptions& options);

// Everything a session runs with.
struct SessionConfig {
  SessionOptions session;
  LocalisationOptions localisation;
};

class Session : public ScanProcessor {
 public:
  // `line_map` (may be empty) stays fixed; `point_map` is extended by the session.
  Session(const SessionConfig& config, LaserMounting mounting, LineMap line_map,
          PointMap point_map);
  Session(const Session&) = delete;
  Session& operator=(const Session&) = delete;

  IterationRecord Process(const Iteration& iteration) override;
  // The iteration as recorded: the recorded decision replaces the localisation; the map, the
  // laser signature, the drift and the loop closures follow as they did (replay.hpp).
  IterationRecord Replay(const Iteration& iteration, const RecordedIteration& recorded) override;

  // With loop_closure.tracking_path_m, renders the whole map from every node: until then the
  // point map held only the nodes tracked against.
  void Finish() override;
  const PointMap& point_map() const override { return point_map_; }
  const LineMap& line_map() const { return line_map_; }
  const LaserMounting& mounting() const override { return mounting_; }
  std::size_t iterations() const { return count_; }
  const LaserSignature& signature() const { return signature_; }
  const LoopCloser& loop_closer() const { return loop_; }
  std::vector<std::optional<Pose2D>> CorrectedPostures() const override;
  const PoseGraph* pose_graph() const override;
  const OdometryModel* odometry_model() const override;
  const OdometryCalibration* odometry_calibration() const override;
  std::optional<MapSignature> map_signature() const override { return map_signature_; }
  // What the final map matching did (none before Finish, or with it off).
  std::optional<FinalMatchSummary> final_match() const override { return final_match_; }

 private:
  // One iteration, localised, or replayed from `recorded` when it is given.
  IterationRecord Step(const Iteration& given, const RecordedIteration* recorded);
  // `given`, or a copy in `stripped` without its odometry: with ignore_odometry, or while the
  // odometry has not moved since the first scan and the ranges did (`frozen` then says so).
  const Iteration& UsableOdometry(const Iteration& given, std::optional<Iteration>& stripped,
                                  bool& frozen);
  // A localised scan with no odometry to predict from: searched for over the motion seen lately.
  MapView View() const;
  Pose2D Predict(const Iteration& iteration) const;
  bool ShouldLocalise(const Iteration& iteration) const;
  bool Turning(const Iteration& iteration) const;
  LocalisationResult LocaliseCandidates(const Pose2D& prediction, const Iteration& iteration,
                                        const std::vector<Candidate>& search,
                                        const LocalisationOptions& options) const;
  void AddSearchCandidates(IterationRecord& record, const LaserScan& scan,
                           std::vector<Candidate>& candidates) const;
  // The window of a scan without odometry (SearchesMotion), into `record`.
  void MotionSearchWindow(IterationRecord& record) const;
  // The wide search over `record`'s window, its postures appended to `candidates`.
  void Search(IterationRecord& record, const LaserScan& scan,
              std::vector<Candidate>& candidates) const;
  void LocaliseInto(IterationRecord& record, const Iteration& iteration);
  void RestoreLocalised(IterationRecord& record, const Iteration& iteration,
                        const RecordedIteration& recorded);
  void JudgeCorrection(IterationRecord& record, const RankedCandidate& kept);
  void KeepDrift(const IterationRecord& record);
  bool TakesPrediction(const IterationRecord& record, const RankedCandidate& kept) const;
  // Rule 2's E_max in force for the next localisation and the signature's bound, into `record`.
  LocalisationOptions BoundedOptions(IterationRecord& record) const;
  LocalisationOptions SignatureBoundedOptions() const;
  // The odometry's prediction as the refinement's prior, when motion_prior is on.
  void AddMotionPrior(LocalisationOptions& options, const Pose2D& prediction,
                      const Iteration& iteration) const;
  // The drift after a localised scan, confirmed or not; `was_lost` before it.
  void AfterLocalised(IterationRecord& record, const Iteration& iteration, bool was_lost);
  bool OnNewGround(const IterationRecord& record, const LaserScan& scan) const;
  void MaybeExtend(IterationRecord& record, const LaserScan& scan);
  void MaybeCloseLoop(IterationRecord& record, const Iteration& iteration,
                      const std::optional<Eigen::Matrix3d>& covariance);
  // With loop_closure.tracking_path_m: the session tracks against the newest nodes only.
  bool Tracking() const;
  bool WithdrawDisputedTurn(IterationRecord& record);
  // The iteration with its odometry calibrated (a copy in `calibrated` once the calibrated
  // odometry differs from the log's).
  const Iteration& CalibratedOdometry(const Iteration& usable,
                                      std::optional<Iteration>& calibrated);
  // What the scan teaches the calibration; `raw` is the log's odometry at it.
  void LearnCalibration(const IterationRecord& record, const std::optional<Pose2D>& raw);
  void RenderTracked();
  void MatchOnFinalMap();

  SessionOptions options_;
  LocalisationOptions localisation_;
  LaserMounting mounting_;
  LineMap line_map_;
  PointMap point_map_;
  std::size_t tracked_from_node_ = 0;  // the oldest node in the map tracked against
  LaserSignature signature_;
  LaidScanSample laid_;  // confirmed scans laid on the map, for the map's own signature
  std::optional<MapSignature> map_signature_;
  std::optional<FinalMatchSummary> final_match_;
  DriftTracker drift_;
  CorrectionGate gate_;
  CorrectionDrift correction_drift_;
  LoopCloser loop_;
  std::size_t count_ = 0;
  Pose2D last_pose_;  // T_world_robot of the previous iteration
  MotionWindow motion_;
  FrozenOdometry frozen_;
  std::optional<Pose2D> last_odometry_;
  Pose2D last_localised_odometry_;  // odometry at the last localised iteration
  std::optional<Pose2D> last_inserted_pose_;
  OdometryCalibration calibration_;
  std::optional<Pose2D> raw_odometry_;  // the log's odometry at the last iteration with one
  Pose2D calibrated_odometry_;          // ... and the calibrated odometry there
  bool calibrated_apart_ = false;       // the calibrated odometry has left the log's
  // The log's odometry and the posture at the last confirmed scan, while nothing moved the
  // session since: the start of the calibration's next sample.
  struct CalibrationAnchor {
    Pose2D odometry, posture;
  };
  std::optional<CalibrationAnchor> calibration_anchor_;
};

}  // namespace scanloc
