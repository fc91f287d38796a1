#pragma once
// What one iteration did, for the operator, and the interface of what produces it: a session that
// grows its map (Session) or a localisation on a saved map (Localiser).

#include <optional>
#include <string>
#include <vector>

#include "scanloc/maps/point_map.hpp"
#include "scanloc/session/correction_drift.hpp"
#include "scanloc/session/correction_gate.hpp"
#include "scanloc/session/final_map_matching.hpp"
#include "scanloc/session/iteration.hpp"
#include "scanloc/session/localisation.hpp"
#include "scanloc/session/loop_closure.hpp"
#include "scanloc/session/map_signature.hpp"
#include "scanloc/session/odometry_calibration.hpp"
#include "scanloc/session/replay.hpp"
#include "scanloc/session/turn_dispute.hpp"
#include "scanloc/session/wide_search.hpp"

namespace scanloc {

// The cost that tells held hypotheses apart (their truncated mean distance,
// hypothesis_evidence.hpp) at one scan that localised one.
struct CostAt {
  std::size_t scan = 0;
  double cost = 0.0;
  // The Likelihood Test's expected value and match ratio there (Outmatched).
  double expect_value_m = 0.0;
  double match_ratio = 0.0;
};

// A posture held while the scans have not yet told it from others (§3.3, last paragraph): carried
// with the odometry, confirmed or discarded by the next scans' Likelihood Tests.

struct Hypothesis {
  Pose2D T_world_robot;
  int confirmed_in_row = 0;    // scans in a row whose rules validated it, up to now
  int unconfirmed_in_row = 0;  // scans in a row whose rules did not
  int confirmations = 0;       // scans that validated it since it was found
  double cost = 0.0;           // (3.11) at the last scan that localised it
  bool validated = false;      // at the last scan that localised it
  // The rules' verdict at that scan (rule 3 among the held hypotheses included), and the
  // Likelihood Test of its refinement there.
  Verdict verdict = Verdict::kNoValidPairs;
  double expect_value_m = 0.0;
  double match_ratio = 0.0;
  double truncated_mean_m = 0.0;  // TruncatedMeanDistance there (hypothesis_evidence.hpp)
  int searches = 0;  // global searches since it was found (the user's initial posture counts one)
  // A posture confirmed before and since lost: held until another has been validated
  // confirm_after scans in a row.
  bool held = false;
  std::vector<CostAt> costs;  // its newest costs, oldest first (hypothesis_evidence.hpp)
};

// Everything the operator may want to know about one iteration.
struct IterationRecord {
  std::size_t index = 0;
  double timestamp_s = 0.0;
  std::string origin;
  bool skipped = false;  // not localised: the robot had not moved enough
  bool first = false;    // the first iteration of a session without a prior map
  Pose2D prediction;     // odometry prediction, T_world_robot
  // Every candidate and refinement, when the scan was localised.
  std::optional<LocalisationResult> localisation;
  Pose2D T_world_robot;               // the posture kept for this scan
  Verdict verdict = Verdict::kValid;  // the rules on the kept posture
  bool validated = false;
  double max_expect_value_m = 0.0;        // rule 2's E_max in force
  double signature_expect_value_m = 0.0;  // the laser signature's bound (in force or not)
  // The correction gate's bound in force (none until learned), and whether the kept refinement
  // went beyond it (then it was neither confirmed nor kept: the scan took the prediction).
  std::optional<CorrectionBound> correction_bound;
  bool beyond_odometry = false;
  // The kept refinement was confirmed, but its correction would have added up, with the recent
  // ones, to a slide (correction_drift.hpp), and the prediction as given passed the rules too:
  // the correction was refused, and the scan was confirmed at the prediction.
  bool slide_refused = false;
  // The slide check of the confirmed correction, once the check has learned its bound.
  std::optional<SlideCheck> slide_check;
  // The index of the refinement the rules ranked first, when the session kept one that matched
  // more pairs at a lower truncated mean distance instead (tighter_refinement.hpp); -1 otherwise.
  int outranked_refinement = -1;
  // The wide search, when the session was lost before this scan or the scan had no odometry
  // (motion_search: the window of the motion seen lately): its window and what it found.
  std::optional<SearchWindow> search_window;
  std::optional<WideSearchResult> search;
  bool motion_search = false;
  // Localised with no odometry to predict from (none in the log, ignored, or frozen).
  bool without_odometry = false;
  // Localisation on a saved map without the log's odometry: the odometry was the scan's match on
  // the scan before (ScanOdometry), and how many hypotheses were searched for around themselves
  // over the motion seen lately (where that match failed).
  bool odometry_from_scans = false;
  std::size_t motion_searched_hypotheses = 0;
  // The log's odometry had not moved since the first scan while the ranges did: it was not used
  // for this scan (session.motion_search.frozen_odometry_range_change_m).
  bool odometry_frozen = false;
  // Localisation on a saved map: this scan's costs did not enter the held hypotheses' evidence,
  // since it was no new view (LocaliserOptions::evidence_from_new_views).
  bool not_evidence = false;
  // Localisation on a saved map (Localiser): "searching", "ambiguous", "tentative" or "confirmed"
  // ("" in a session), and the hypotheses held after this scan, best first. A scan without a
  // hypothesis has no posture (posed false): it is left out of the trajectory.
  std::string state;
  std::vector<Hypothesis> hypotheses;
  // The hypotheses discarded at this scan: "(x, y, θ): why" (not validated k scans in a row, or
  // costlier than another beyond chance).
  std::vector<std::string> discarded;
  bool posed = true;
  bool lost = false;       // lost after this scan (several unconfirmed in a row)
  bool recovered = false;  // confirmed after being lost
  bool inserted = false;   // the scan extended the map
  // Unconfirmed, the scan kept the prediction where the map covers too little of it to judge it,
  // and extends the map there (new_ground.hpp).
  bool new_ground = false;
  std::size_t carved = 0;      // map points removed by this scan's free space
  std::size_t map_points = 0;  // after this iteration
  // The loop closure tried after this scan extended the map, when one was due.
  std::optional<ClosureAttempt> closure;
  // The tracker's heading correction that closure disputed: withdrawn, the scan took the
  // prediction (turn_dispute.hpp).
  std::optional<TurnDispute> turn_dispute;
  double insert_s = 0.0, total_s = 0.0;

  // The refinement kept, when the scan was localised.
  const RankedCandidate* Kept() const { return localisation ? localisation->Kept() : nullptr; }
};

// The record of iteration number `index` as it starts: where and when it came from. Throws
// std::invalid_argument when the scan is inconsistent (ranges and layout disagree).
IterationRecord BeginRecord(const Iteration& iteration, std::size_t index);

// Turns each iteration of a sequence into its record.
class ScanProcessor {
 public:
  virtual ~ScanProcessor() = default;
  virtual IterationRecord Process(const Iteration& iteration) = 0;
  // Resuming: processes the iteration as `recorded` says it was (replay.hpp) and returns a record
  // of what the counts and the trajectory need. Throws ReplayMismatch when the replay disagrees
  // with the record, std::logic_error when the processor cannot resume.
  virtual IterationRecord Replay(const Iteration& iteration, const RecordedIteration& recorded);
  // Called once after the last iteration, before the map is written.
  virtual void Finish() {}
  // The map: while processing, the one scans are localised against; after Finish, the whole map.
  virtual const PointMap& point_map() const = 0;
  virtual const LaserMounting& mounting() const = 0;
  // Postures corrected after the fact by loop closure, by record index (none for a record the
  // correction does not reach); empty when the processor corrects nothing.
  virtual std::vector<std::optional<Pose2D>> CorrectedPostures() const { return {}; }
  // How well the finished map explains the scans that built it (after Finish); none when the
  // processor does not build the map.
  virtual std::optional<MapSignature> map_signature() const { return {}; }
  // The pose graph, when the processor keeps one.
  virtual const PoseGraph* pose_graph() const { return nullptr; }
  // The odometry model its loop closures taught, when the processor keeps a pose graph.
  virtual const OdometryModel* odometry_model() const { return nullptr; }
  // The odometry's calibration learned from the confirmed steps, when the processor learns one.
  virtual const OdometryCalibration* odometry_calibration() const { return nullptr; }
  // What the final map matching did (final_map_matching.hpp), when the processor ran it.
  virtual std::optional<FinalMatchSummary> final_match() const { return {}; }
};

}  // namespace scanloc
