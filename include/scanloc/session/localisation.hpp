#pragma once
// Localise one scan against a map from some candidate postures: the operation every caller shares
// (the session, `scanloc test`, `scanloc refine`, `scanloc compare`). Each candidate is simulated
// and judged by the Likelihood Test and the rules (§3.3); the chosen ones are refined by
// minimising the Likelihood Distance (§3.5), and the refined postures are judged and ranked again
// (the chapter's refine-then-validate). The result keeps every candidate and every refinement.

#include <optional>
#include <string>
#include <vector>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/likelihood/candidate_ranking.hpp"
#include "scanloc/refinement/refiner.hpp"
#include "scanloc/session/candidate.hpp"

namespace scanloc {

// One candidate posture as judged by the Likelihood Test and ranked by the rules: a candidate as
// given, or the refinement of one.
struct RankedCandidate {
  Candidate candidate;   // as given: label and T_world_robot
  Pose2D T_world_robot;  // the posture judged: the candidate's, or its refinement's
  Pose2D T_world_laser;  // the same, of the laser
  LikelihoodTestResult test;
  LikelihoodDistanceResult distance;
  double cost = 0.0;  // (3.11)
  Verdict verdict = Verdict::kValid;
  int rank = -1;  // 0 for the best valid one, -1 when not valid
  // A refinement's: the index of the evaluated candidate it started from, and its result.
  int from = -1;
  std::optional<RefinementResult> refinement;
};

// Which candidates are refined.
enum class RefinePolicy {
  kNone,       // none: the Likelihood Test of the candidates as given (`scanloc test`)
  kBestValid,  // the valid ones best first, up to a number; when none is valid, the cheapest
  kValidOnly,  // the valid ones best first, up to a number; none when none is valid
  // kBestValid's, and the first candidate (a session's odometry prediction) whatever the rules
  // said of it: a posture that fails rule 2 as given may fit once refined, and a turned
  // candidate that passes may not refine to the right heading. When no refinement passes, the
  // cheapest of them all is kept, the first's included.
  kBestValidAndFirst,
  kAll,  // every candidate (`scanloc refine`, the chapter's Tables 2, 5, 6, 8)
};

// The stages' options a localisation runs with (each declared with its stage).
struct LocalisationOptions {
  ScoringOptions scoring;
  ValidationOptions validation;
  RefinerOptions refiner;
};

struct LocalisationResult {
  std::vector<RankedCandidate> evaluated;  // every candidate as given, in input order
  int best_evaluated = -1;                 // index of the best valid one, or -1
  std::vector<RankedCandidate> refined;    // the refinements, in the order they were made
  int best_refined = -1;                   // index of the best valid refinement, or -1
  // The refinement kept: the best valid one; when none is valid, the cheapest by (3.11) as the
  // best guess (flagged). -1 when nothing was refined.
  int kept = -1;
  // Degenerate data, said rather than hidden: "the map is empty", "the scan has no valid range".
  std::vector<std::string> problems;
  double evaluate_s = 0.0, refine_s = 0.0;

  // The kept refinement, or null.
  const RankedCandidate* Kept() const { return kept >= 0 ? &refined[kept] : nullptr; }
  // A valid posture was found: among the refinements when there are any, else among the
  // candidates as given.
  bool validated() const { return refined.empty() ? best_evaluated >= 0 : best_refined >= 0; }
};

// Localises `scan` seen from the robot postures `candidates` (laser at mounting.LaserPose);
// `max_refined` bounds the refinements of RefinePolicy::kBestValid.
LocalisationResult Localise(const MapView& map, const LaserScan& scan,
                            const std::vector<Candidate>& candidates, const LaserMounting& mounting,
                            const LocalisationOptions& options, RefinePolicy policy,
                            int max_refined = 0);

}  // namespace scanloc
