#pragma once
// What the report reads from a run folder's iterations.jsonl (one JSON record per iteration, as
// ToJson(IterationRecord) writes it): the file format, not the session's C++ types, so that a run
// folder written by another version still renders. Fields the report does not show are ignored.

#include <optional>
#include <string>
#include <vector>

#include "scanloc/geometry/pose2d.hpp"
#include "scanloc/likelihood/likelihood_test.hpp"

namespace scanloc {

// One candidate posture and its Likelihood Test.
struct CandidateRow {
  std::string label;
  Pose2D T_world_robot;
  std::optional<Pose2D> T_world_laser;
  LikelihoodTestResult test;                      // MP, NVP, histogram, EV, Disp
  std::optional<double> distance_expect_value_m;  // Likelihood Distance EV (§3.5)
  std::optional<double> cost;                     // (3.11)
  bool valid = false;
  std::string reason;  // "valid" or the rule that rejected it
  int rank = -1;
};

// The chosen candidate's refinement: the test before and after.
struct RefinementRow {
  Pose2D T_world_laser;  // refined
  bool converged = false;
  int iterations = 0;
  LikelihoodTestResult before, after;
  std::optional<double> distance_expect_value_before_m, distance_expect_value_after_m;
  bool degenerate = false;
  std::string degeneracy;
  double time_s = 0.0;
};

// A refined candidate as re-validated after its refinement (when the session refines several).
struct RefinedCandidateRow {
  std::string candidate;
  Pose2D T_world_laser;
  std::optional<double> cost, expect_value_m, match_ratio;
  bool valid = false;
  std::string reason;
  int rank = -1;
};

// A loop closure tried after a scan (a session run with loop closure on).
struct ClosureRow {
  bool accepted = false;  // it confirmed a batch of agreeing closures
  std::string reason;     // "accepted", or why not
  std::size_t node = 0, old_node = 0, old_iteration = 0;
  // The closure's measurement, the scan seen from the old scan: present when a posture was
  // refined against the old part of the map.
  std::optional<Pose2D> T_old_robot;
  std::optional<Pose2D> T_world_robot_matched;  // the scan's posture matched on the old nodes
  // The largest node displacement of the graph's solve after this closure (absent in run folders
  // older than the field).
  std::optional<double> largest_shift_m;
};

struct IterationRow {
  std::size_t index = 0;
  double timestamp_s = 0.0;
  std::string origin;
  bool skipped = false;
  bool first = false;
  Pose2D prediction;
  Pose2D T_world_robot;
  bool validated = false;
  std::string reason;
  bool inserted = false;
  std::size_t map_points = 0;
  double evaluate_ms = 0.0, refine_ms = 0.0, insert_ms = 0.0, total_ms = 0.0;
  std::vector<CandidateRow> candidates;
  std::string chosen;  // the chosen candidate's label, empty when none
  std::vector<std::string> problems;
  std::optional<RefinementRow> refinement;
  std::vector<RefinedCandidateRow> refined_candidates;
  // Rule 2's E_max in force and the laser signature's bound (absent in older run folders).
  std::optional<double> max_expect_value_m, signature_expect_value_m;
  bool lost = false;       // lost after this scan
  bool recovered = false;  // confirmed after being lost
  bool searched = false;   // the wide search added candidates
  // A localisation on a saved map: its state after this scan and the hypotheses it held ("" and 0
  // in a session).
  std::string state;
  std::size_t hypotheses = 0;
  bool posed = true;  // false: no posture (a localisation still searching)
  std::optional<ClosureRow> closure;

  // Localised but not validated: what the operator should look at.
  bool flagged() const { return !skipped && !first && !validated; }
  // "first", "skipped", "validated" or "flagged".
  const char* status() const;
  // The chosen candidate, or nullptr.
  const CandidateRow* chosen_candidate() const;
  // The old scan an accepted loop closure after this scan closed with.
  std::optional<std::size_t> closed_with() const;
};

// Reads one record; throws std::runtime_error saying which field is missing or of the wrong type
// (e.g. "candidates[2].likelihood_test.histogram: expected an array of whole numbers").
IterationRow IterationRowFromJson(const std::string& json_text);

struct IterationRows {
  std::vector<IterationRow> rows;  // rows[i].index == i
  // Set when the last line was cut short (the session was killed while writing it): it is left
  // out and said, not taken for a malformed file.
  bool truncated_last_line = false;
};

// Reads iterations.jsonl. A malformed line throws ParseError naming the file, the line and what
// was expected; a missing file throws std::runtime_error.
IterationRows ReadIterationRows(const std::string& path);

}  // namespace scanloc
