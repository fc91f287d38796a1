#pragma once
// Localisation on a saved map, which it never changes, from an unknown start (the localise issue).
// Without a posture it searches the whole map (WideSearch over every position and heading); the
// refined candidates that pass rules 1–3 are all held as hypotheses (§3.3, last paragraph: "store
// the posture candidates that comply to the rules 1, 2, 3 and confirm or discard them as the
// system progresses"). Each is carried with the odometry and localised again at every scan; one
// the rules stop validating is discarded, and so is one that cost more than another at the same
// scans beyond chance (hypothesis_evidence.hpp). The posture is confirmed when a single hypothesis
// is left and the rules validated it confirm_after scans in a row; while several are held the
// output says "ambiguous" and lists them. A confirmed posture that the rules stop validating (a
// robot carried elsewhere) is lost: it is held on as one hypothesis among those a new search finds.
// Without odometry (none in the log, session.ignore_odometry, or odometry frozen while the scans
// move: motion_search.hpp) each hypothesis stays where it was and, when the rules confirm nothing
// there or the refinement had to move beyond the minima, the map is searched around it over the
// motion the confirmed posture showed lately (the recovery's initial window before).

#include <optional>
#include <string>
#include <vector>

#include "scanloc/maps/line_map.hpp"
#include "scanloc/maps/point_map.hpp"
#include "scanloc/session/place_bound.hpp"
#include "scanloc/session/scan_odometry.hpp"
#include "scanloc/session/scan_processor.hpp"
#include "scanloc/session/session.hpp"

namespace scanloc {

struct LocaliserOptions {
  // The global search: its grid, how many distinct postures it hands to the refinement.
  WideSearchOptions search = DefaultGlobalSearch();
  // Scans in a row the rules must validate the only hypothesis left before it is confirmed; and
  // a global search made after it was found, once the robot moved, must have found no other.
  int confirm_after = 3;
  // Until a posture is confirmed, and while no hypothesis is held, the whole map is searched
  // again once the odometry moved this far or turned this much since the last search (a new view
  // may show a place missed before; the same view would not). Without odometry that could tell
  // the travel, holding nothing, the scan's ranges must have moved since the last search's by
  // more than session.frozen_odometry_range_change_m (the median over the beams).
  double research_distance_m = 0.5;
  double research_turn_rad = 0.8;
  // A hypothesis not yet confirmed is discarded after this many unconfirmed scans in a row; a
  // confirmed posture is lost after lost_after_unconfirmed.
  int drop_after_unconfirmed = 2;
  int lost_after_unconfirmed = 5;
  // A hypothesis is discarded once another cost less (by the truncated mean distance) at the
  // same scans beyond chance (hypothesis_evidence.hpp) and by at least this fraction of the
  // cheaper's cost: twins in two identical rooms settle a few percent apart at every scan, a
  // look-alike whose pillar the view shows costs 91 % more (tests/localiser_test.cpp).
  double min_cost_excess_ratio = 0.1;
  // Rule 2's prior E_max on a point map a session wrote is that map's own signature (the bound
  // in the summary.json beside it, map_signature.hpp), until the localiser's signature learned.
  bool map_signature = true;
  // ... and rule 2's bound at each place is raised by how much worse than the map's median its
  // nearest sampled scans fit (place_bound.hpp), when the summary holds them.
  bool place_bound = true;
  // Until a posture is confirmed every scan is localised, even while the robot stands still: the
  // rules judge each held hypothesis at every scan (one they reject goes), where skipping them
  // would leave a robot that stopped unconfirmed until it moves again. Its costs count as
  // evidence only at a new view (evidence_from_new_views).
  bool track_while_still = true;
  // A hypothesis that passes the rules alone but costs (3.11) more than rule 3 allows against
  // the cheapest held one is not validated at that scan. It counts towards its discarding
  // (drop_after_unconfirmed) only when its truncated mean distance is above that one's too: in a
  // corridor a posture a metre or two off can match fewer beams more tightly and cost less by
  // (3.11) at many scans, while the true one has the lower truncated mean at nearly every scan.
  // Off: it always counts.
  bool relative_cost_needs_truncated_mean = true;
  // While ambiguous, the posture output stays with the hypothesis it followed at the scan before
  // (the one within same_posture_m and same_posture_rad of it, carried by the odometry) while
  // that one is validated and no other cost at least min_cost_excess_ratio less at the scans both
  // were localised at: held look-alikes whose costs tie do not make the output jump between
  // places from scan to scan. Off: the best ranked is output at every scan.
  bool steady_output = true;
  // A hypothesis is also discarded once another outmatched it at the same scans (Outmatched,
  // hypothesis_evidence.hpp): pairs matched tighter beyond chance by at least
  // min_cost_excess_ratio, and a truncated mean lower on average too.
  bool drop_outmatched = true;
  // Without the log's odometry (none, session.ignore_odometry, or frozen), the scans' own:
  // each scan matched on the scan before (ScanOdometry) carries the hypotheses as a wheel
  // odometry would. Off: each hypothesis stays where it was and is searched for around itself
  // when the rules confirm nothing there (the motion search alone).
  bool scan_odometry = true;
  // A scan's costs enter the held hypotheses' evidence (the histories hypothesis_evidence.hpp
  // compares) only when it is a new view by the map's own standard: the odometry moved or turned
  // since the last scan whose costs did as much as a session needs to insert a scan into the map
  // (session.insert_translation_m, session.insert_rotation_rad). Scans from nearly the same place
  // see the same map errors, so they are one view's evidence, not independent trials: on the maps
  // of the robustness harness, ten scans over half a metre of ACES's corridors let a look-alike
  // that fitted 11–29 % tighter there outmatch the true place, and a wrong place was confirmed
  // on 4 of 30 starts (docs/BENCHMARKS.md). Off: every localised scan is evidence.
  bool evidence_from_new_views = true;
  int max_hypotheses = 8;  // the best by confirmations, then cost, are kept
  // Hypotheses closer than both of these are one (the better kept).
  double same_posture_m = 0.3;
  double same_posture_rad = 0.1;

  static WideSearchOptions DefaultGlobalSearch();
  // Throws std::invalid_argument naming the first option out of its domain.
  void Validate() const;
};

struct LocaliserConfig {
  SessionOptions session;  // the candidates around a hypothesis and the localise gate
  LocalisationOptions localisation;
  LocaliserOptions localiser;
  std::optional<Pose2D> initial_pose;  // T_world_robot when known: the first hypothesis
  PlaceBound place_bound;              // rule 2's bound raised where the map fits worse
};

class Localiser : public ScanProcessor {
 public:
  // `line_map` and `point_map` (either may be empty, not both) stay as they are.
  Localiser(const LocaliserConfig& config, LaserMounting mounting, LineMap line_map,
            PointMap point_map);

  IterationRecord Process(const Iteration& iteration) override;
  const PointMap& point_map() const override { return point_map_; }
  const LaserMounting& mounting() const override { return mounting_; }
  const std::vector<Hypothesis>& hypotheses() const { return hypotheses_; }
  bool confirmed() const { return confirmed_; }

 private:
  MapView View() const { return {line_map_.empty() ? nullptr : &line_map_, &point_map_}; }
  const Iteration& UsableOdometry(const Iteration& given, std::optional<Iteration>& replaced,
                                  bool& frozen);
  void LearnMotion(const IterationRecord& record, const Iteration& iteration);
  bool SearchDue(const Iteration& iteration) const;
  bool EvidenceDue(const Iteration& iteration) const;
  bool ViewChanged(const LaserScan& scan) const;
  LocalisationResult LocaliseHypothesis(const Hypothesis& h, const Iteration& iteration,
                                        bool turning, bool& searched) const;
  void Search(IterationRecord& record, const Iteration& iteration);
  void Track(IterationRecord& record, const Iteration& iteration);
  void Prune(IterationRecord& record);
  std::string OutCosted(const Hypothesis& h) const;
  bool Costed(const Hypothesis& h) const;
  LocalisationOptions BoundedOptions(IterationRecord& record) const;
  double BoundAt(const Pose2D& T_world_robot) const;
  void Conclude(IterationRecord& record);
  std::size_t Output() const;

  LocaliserConfig config_;
  LaserMounting mounting_;
  LineMap line_map_;
  PointMap point_map_;
  std::vector<Hypothesis> hypotheses_;  // best first
  LaserSignature signature_{config_.session.signature};
  LocalisationOptions in_force_;  // this scan's: rule 2's E_max from the signature
  bool confirmed_ = false;
  bool lost_ = false;  // a confirmed posture was lost and not yet found again
  std::size_t count_ = 0;
  std::optional<Pose2D> last_odometry_;
  std::optional<Pose2D> last_localised_odometry_;
  std::optional<Pose2D> last_evidence_odometry_;  // the odometry at the last evidence scan
  bool evidence_ = true;                          // this scan's costs are evidence
  std::optional<Pose2D> last_search_odometry_;
  std::optional<Pose2D> last_search_output_;  // without odometry: the posture output there
  std::optional<LaserScan> last_search_scan_;
  std::optional<Pose2D> last_output_;  // the posture output at the scan before, carried along
  bool search_due_ = false;            // a confirmed posture was just lost
  LikelihoodField search_field_;       // the storage of every global search's field
  FrozenOdometry frozen_{config_.session.motion_search.frozen_odometry_range_change_m};
  // Without the log's odometry, the scans' own (scan_odometry.hpp).
  ScanOdometry scan_odometry_{point_map_.options(), config_.localisation, mounting_};
  bool odometry_from_scans_ = false;
  MotionWindow motion_{config_.session.motion_search};
  std::optional<Pose2D> last_confirmed_;  // the confirmed posture at the scan before, if any
};

}  // namespace scanloc
