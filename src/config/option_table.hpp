#pragma once
// The one declaration of every configuration option: its key in the JSON config, the field it
// sets, the range of sane values and its meaning. The JSON reader (ApplyJson), the writer
// (ToJson), the range checks and the help text (`scanloc options`) are all derived from it.
//
// A visitor is called as
//   v(key, field, Bounds, meaning)         numbers (int, double, std::optional<double>)
//   v(key, field, meaning)                 booleans and enumerations (by name)
//   v(key, pose, position, heading, meaning)  a Pose2D written as [x, y, yaw]
// `field` is a reference into the Config (const when the Config is).

#include <cmath>

#include "scanloc/config/config.hpp"

namespace scanloc::config_table {

// Inclusive range of the values a key accepts; the stage's own Validate() checks the finer
// domain (e.g. > 0), these bounds refuse the absurd (1e-300 m slots, a billion neighbours).
struct Bounds {
  double min = 0.0;
  double max = 0.0;
};

inline constexpr Bounds kDistance{1e-4, 1e3};  // metres: 0.1 mm to 1 km
inline constexpr Bounds kAngle{0.0, M_PI};     // radians: none to half a turn
inline constexpr Bounds kPosition{-1e6, 1e6};  // metres, world coordinates
inline constexpr Bounds kHeading{-2.0 * M_PI, 2.0 * M_PI};
inline constexpr Bounds kIterations{1, 1e5};

template <class C, class V>
void VisitScoring(C& c, V& v) {
  auto& test = c.scoring.test;
  v("likelihood_test.slot_count", test.slot_count, Bounds{2, 1e4}, "NS: histogram slots");
  v("likelihood_test.slot_width_m", test.slot_width_m, Bounds{1e-4, 10},
    "Δslot: width of one histogram slot, m");
  v("likelihood_test.match_threshold_m", test.match_threshold_m, kDistance,
    "T_Map: a pair farther apart is not a match pair, m");
  v("likelihood_test.last_slot_distance_m", test.last_slot_distance_m, Bounds{0, 1e3},
    "Δmax: the distance standing for the last slot, m; 0: 3/2·NS·Δslot");
  v("likelihood_distance.kernel", c.scoring.distance.kernel,
    "robust kernel of the Likelihood Distance: cauchy, huber or tukey");
  v("likelihood_distance.scale_m", c.scoring.distance.scale_m, kDistance,
    "the kernel's scale c: distances well above it weigh little, m");
  v("point_simulation.footprint_factor", c.scoring.simulation.footprint_factor, Bounds{0, 100},
    "a map point hides the beams within ±factor·spacing/2 of its bearing; 0: plain (3.7)");
  v("line_sampling_m", c.line_sampling_m, Bounds{1e-4, 10},
    "spacing when a line map is sampled to points (§3.2.2), m");
  v("point_map.cell_size_m", c.point_map.cell_size_m, Bounds{0, 100},
    "de-duplication: a point is not inserted into an occupied square cell of this side, m; 0: "
    "off");
  v("point_map.max_point_spacing_m", c.point_map.max_point_spacing_m, Bounds{0, 100},
    "upper bound of the spacing recorded with a point (bounds what it occludes), m");
  auto& laser = c.mounting.T_robot_laser;
  v("mounting.x_m", laser.x_m, Bounds{-100, 100}, "laser position ahead of the robot base, m");
  v("mounting.y_m", laser.y_m, Bounds{-100, 100}, "laser position left of the robot base, m");
  v("mounting.yaw_rad", laser.yaw_rad, kHeading, "laser heading on the robot, rad");
}

template <class C, class V>
void VisitValidation(C& c, V& v) {
  auto& rules = c.validation;
  v("validation.min_match_ratio", rules.min_match_ratio, Bounds{0, 1},
    "rule 1 MinMatchRatio: MatchPairs/NVP must exceed it");
  v("validation.max_expect_value_m", rules.max_expect_value_m, Bounds{1e-6, 1e3},
    "rule 2 E_max: ExpectValue must stay below it, m (the chapter's 0.15° laser: 0.05)");
  v("validation.alpha_m", rules.alpha_m, Bounds{0, 1e3},
    "(3.11) α: cost per unit ratio of non-match pairs, m; also Error Descent's criterion");
  v("validation.max_cost_ratio", rules.max_cost_ratio, Bounds{1, 1e6},
    "rule 3: rejected when cost > max_cost_ratio · best cost");
  v("validation.much_less_factor", rules.much_less_factor, Bounds{1, 1e6},
    "rules 4 and 5: a << b reads as much_less_factor · a < b");
}

template <class C, class V>
void VisitCeres(C& c, V& v) {
  auto& o = c.refiner.ceres;
  v("refinement.ceres.max_outer_iterations", o.max_outer_iterations, kIterations,
    "re-simulations (new correspondences)");
  v("refinement.ceres.max_solver_iterations", o.max_solver_iterations, kIterations,
    "Levenberg–Marquardt iterations per outer iteration");
  v("refinement.ceres.translation_tolerance_m", o.translation_tolerance_m, Bounds{1e-9, 10},
    "converged when an outer step moves less than this, m ...");
  v("refinement.ceres.rotation_tolerance_rad", o.rotation_tolerance_rad, Bounds{1e-9, 1},
    "... and turns less than this, rad");
  v("refinement.ceres.incidence", o.incidence,
    "residual weighting by the beam's incidence: none, cosine or gate");
  v("refinement.ceres.point_association", o.point_association,
    "point maps: pair a beam with simulated-hit or nearest-endpoint");
  v("refinement.ceres.max_incidence_rad", o.max_incidence_rad, Bounds{1e-3, M_PI / 2},
    "gate: beams more grazing than this are dropped, rad");
  v("refinement.ceres.max_residual_m", o.max_residual_m, Bounds{-1e3, 1e3},
    "pairs farther apart are left out, m; <= 0: T_Map");
  v("refinement.ceres.line_fit_neighbours", o.line_fit_neighbours, Bounds{2, 1000},
    "point maps: nearest points that define the local line of a hit");
  v("refinement.ceres.line_fit_radius_m", o.line_fit_radius_m, kDistance,
    "point maps: radius within which those neighbours are taken, m");
  v("refinement.ceres.max_line_thickness", o.max_line_thickness, Bounds{1e-6, 1},
    "point maps: a neighbourhood rounder than this (√(λmin/λmax)) defines no line");
  v("refinement.ceres.degeneracy_ratio", o.degeneracy_ratio, Bounds{0, 1},
    "degenerate when the weakest direction carries less than this fraction of the strongest");
}

template <class C, class V>
void VisitRefinement(C& c, V& v) {
  v("refinement.method", c.refiner.method, "refinement method: ceres, error-descent or icp");
  VisitCeres(c, v);
  auto& descent = c.refiner.error_descent;
  v("refinement.error_descent.initial_step_m", descent.initial_step_m, kDistance,
    "translation step of the first level, m");
  v("refinement.error_descent.initial_step_rad", descent.initial_step_rad, Bounds{1e-6, M_PI},
    "rotation step of the first level, rad");
  v("refinement.error_descent.step_levels", descent.step_levels, Bounds{1, 30},
    "step sizes tried, each half the last");
  v("refinement.error_descent.max_moves_per_level", descent.max_moves_per_level, kIterations,
    "a level ends after this many moves");
  v("refinement.error_descent.diagonal_moves", descent.diagonal_moves,
    "true: the 26 neighbours of the 3×3×3 stencil; false: the 6 axis neighbours");
  auto& icp = c.refiner.icp;
  v("refinement.icp.max_correspondence_distance_m", icp.max_correspondence_distance_m, kDistance,
    "pairs farther apart are not correspondences, m");
  v("refinement.icp.max_iterations", icp.max_iterations, kIterations,
    "reaching it without meeting a criterion is 'not converged'");
  v("refinement.icp.transformation_epsilon", icp.transformation_epsilon, Bounds{0, 1},
    "stop when an iteration moves less than this (m², 1 − cos θ)");
  v("refinement.icp.euclidean_fitness_epsilon", icp.euclidean_fitness_epsilon, Bounds{0, 1},
    "stop when the mean squared distance changes by less than this, relatively");
  v("refinement.icp.point_to_plane", icp.point_to_plane,
    "false: point-to-point; true: point-to-line against map normals");
}

template <class C, class V>
void VisitSession(C& c, V& v) {
  auto& s = c.session;
  v("session.heading_spread_rad", s.heading_spread_rad, kAngle,
    "candidates: the prediction turned up to ± this, rad");
  v("session.heading_step_rad", s.heading_step_rad, Bounds{1e-4, M_PI}, "... by this step, rad");
  v("session.max_refined_candidates", s.max_refined_candidates, Bounds{1, 1000},
    "valid candidates refined, best first");
  v("session.refine_prediction", s.refine_prediction,
    "the odometry prediction is refined too when the rules rejected it as given (kept only when "
    "its refinement passes them)");
  v("session.heading_candidates_min_turn_rad", s.heading_candidates_min_turn_rad, kAngle,
    "turned candidates only when the odometry turned more than this, rad");
  v("session.heading_candidates_on_failure", s.heading_candidates_on_failure,
    "... and only when no other candidate passes the rules");
  v("session.localise_translation_m", s.localise_translation_m, Bounds{0, 1e3},
    "a scan is localised when the odometry moved more than this, m ...");
  v("session.localise_rotation_rad", s.localise_rotation_rad, kAngle, "... or turned this, rad");
  v("session.insert_translation_m", s.insert_translation_m, Bounds{0, 1e3},
    "a validated scan extends the map when the robot moved more than this, m ...");
  v("session.insert_rotation_rad", s.insert_rotation_rad, kAngle, "... or turned this, rad");
  v("session.insert_unvalidated", s.insert_unvalidated,
    "let scans that were not validated extend the map");
  v("session.map_new_ground", s.map_new_ground,
    "an unconfirmed scan that kept the prediction where the map, seen from there, pairs with fewer "
    "of its beams than rule 1's ratio extends the map at the prediction (not while lost)");
  v("session.unconfirmed_takes_prediction", s.unconfirmed_takes_prediction,
    "a scan the rules do not confirm keeps the odometry prediction, not its refinement ...");
  v("session.prediction_disproved_cost_ratio", s.prediction_disproved_cost_ratio, Bounds{1, 100},
    "... unless the prediction's cost (3.11) exceeds this many times the refinement's");
  v("session.low_overlap_takes_prediction", s.low_overlap_takes_prediction,
    "a scan whose refinement fails rule 1 (too little of it on the map) keeps the prediction");
  v("session.relative_low_overlap_takes_prediction", s.relative_low_overlap_takes_prediction,
    "an unconfirmed scan whose refinement matches less than the correction gate's overlap "
    "fraction of the recent confirmed scans' median match ratio keeps the prediction");
  v("session.keep_tighter_refinement", s.keep_tighter_refinement,
    "among the valid refinements, keep one at a lower truncated mean distance than the rules' "
    "best when the best matched fewer pairs than the correction gate's overlap fraction of its");
  v("session.motion_prior", s.motion_prior.enabled,
    "the odometry's prediction is a prior on the refinement's position (not its heading) ...");
  v("session.motion_prior_floor_m", s.motion_prior.floor_m, Bounds{1e-6, 100},
    "... σ = this + a growth per metre the odometry moved since the last localised scan, m ...");
  v("session.motion_prior_along_per_m", s.motion_prior.along_per_m, Bounds{0, 100},
    "... growth along the motion, m per m ...");
  v("session.motion_prior_across_per_m", s.motion_prior.across_per_m, Bounds{0, 100},
    "... and across it, m per m");
  v("session.learned_max_expect_value", s.learned_max_expect_value,
    "rule 2's E_max is the laser signature's bound (validation's is its prior); false: recorded "
    "only");
  v("session.signature_window", s.signature.window, Bounds{0, 100000},
    "laser signature: the confirmed scans it remembers; 0: nothing learned");
  v("session.signature_min_samples", s.signature.min_samples, Bounds{1, 100000},
    "laser signature: confirmed scans before its bound differs from validation's E_max");
  v("session.signature_spread_factor", s.signature.spread_factor, Bounds{0.1, 100},
    "laser signature: E_max = median EV + this · robust σ of the remembered EVs");
  v("session.correction_gate_factor", s.correction_gate.factor, Bounds{0, 1e3},
    "a refinement moving the posture further from the odometry's prediction than this many times "
    "the recent confirmed scans' median correction (×√(n+1) after n unconfirmed) is refused; 0: "
    "off");
  v("session.correction_gate_overlap_fraction", s.correction_gate.overlap_fraction, Bounds{0, 1},
    "correction gate: a refinement beyond the bound is refused when it matches fewer beams than "
    "this fraction of the recent confirmed scans' median match ratio ...");
  v("session.correction_gate_weak_axis_ratio", s.correction_gate.weak_axis_ratio, Bounds{1, 1e3},
    "correction gate: ... or that exceeds it in position along a direction this many times less "
    "constrained (σ, the refinement's covariance) than the best");
  v("session.correction_gate_refuses_unvalidated", s.correction_gate.refuse_unvalidated,
    "correction gate: after the first unconfirmed scan in a row, a correction beyond the bound by "
    "a refinement the rules did not validate is refused whatever its support (the scan keeps the "
    "prediction)");
  v("session.correction_gate_unvalidated_one_step", s.correction_gate.unvalidated_one_step,
    "correction gate: ... judged against the bound of one step, not the bound widened by the "
    "unconfirmed stretch (off by default)");
  v("session.correction_gate_agree_factor", s.correction_gate.agree_factor, Bounds{0, 1e3},
    "correction gate: a refused posture stands when the next localised scan lands within this "
    "many median corrections of it");
  v("session.correction_gate_window", s.correction_gate.window, Bounds{0, 100000},
    "correction gate: the confirmed scans it remembers");
  v("session.correction_gate_min_samples", s.correction_gate.min_samples, Bounds{1, 100000},
    "correction gate: confirmed scans before it refuses anything");
  v("session.correction_drift_window_m", s.correction_drift.window_m, Bounds{0, 1e3},
    "confirmed corrections are summed over this much path, m; 0: no slide check");
  v("session.correction_drift_factor", s.correction_drift.factor, Bounds{1e-6, 1e3},
    "a confirmed correction taking that sum beyond this many times the median sum the recent "
    "confirmed scans left (and farther; never below the gate's bound, ×√(1 + path held / window) "
    "while held) is refused as a slide: the scan takes the prediction");
  v("session.correction_drift_samples", s.correction_drift.samples, Bounds{1, 1e6},
    "slide check: sums remembered (the most recent)");
  v("session.correction_drift_min_samples", s.correction_drift.min_samples, Bounds{1, 1e6},
    "slide check: sums learned before it closes (until then a refinement stopped at its "
    "iteration cap still moving along its weakest axis is refused as a slide)");
  v("session.odometry_calibration", s.odometry_calibration.enabled,
    "learn the odometry's distance and turn scales from the confirmed steps, and report them");
  v("session.odometry_calibration_apply", s.odometry_calibration.apply,
    "odometry calibration: scale the odometry by the significant scales before anything uses it");
  v("session.odometry_calibration_window", s.odometry_calibration.window, Bounds{1, 1e7},
    "odometry calibration: confirmed steps remembered (the most recent)");
  v("session.odometry_calibration_min_samples", s.odometry_calibration.min_samples, Bounds{1, 1e7},
    "odometry calibration: steps that moved needed before a scale is applied");
  v("session.odometry_calibration_min_change", s.odometry_calibration.min_change, Bounds{0, 1},
    "odometry calibration: a scale is significant while it stands farther than this from 1 ...");
  v("session.odometry_calibration_significance", s.odometry_calibration.significance,
    Bounds{0, 1e3}, "... and farther than this many of its standard errors");
  v("session.odometry_calibration_min_step_m", s.odometry_calibration.min_step_m, Bounds{0, 1e3},
    "odometry calibration: a sample spans at least this much of the odometry's driving, m ...");
  v("session.odometry_calibration_min_step_rad", s.odometry_calibration.min_step_rad, kAngle,
    "... or this much turning, rad");
  v("session.odometry_calibration_refit_every", s.odometry_calibration.refit_every, Bounds{1, 1e7},
    "odometry calibration: the scales are fitted again after this many steps");
  v("session.odometry_calibration_max_scale", s.odometry_calibration.max_scale, Bounds{1.001, 100},
    "odometry calibration: a scale beyond [1/this, this] is not believed");
  v("session.free_space_margin_m", s.extension.free_space_margin_m, Bounds{0, 100},
    "carving: a point more than margin + margin_per_m·r in front of a return is seen through, m; "
    "0: no carving");
  v("session.free_space_margin_per_m", s.extension.free_space_margin_per_m, Bounds{0, 1},
    "carving: the margin's growth per metre of range r");
  v("session.carve_with_earlier_scans", s.extension.carve_with_earlier_scans,
    "carving: the saved map is carved again, each scan against the points laid after it (with "
    "loop closure on), so that what only the last scans saw does not stay where earlier ones saw "
    "free space");
  v("session.initial_pose", s.initial_pose, kPosition, kHeading,
    "T_world_robot of the first iteration, [x m, y m, yaw rad]");
  v("session.ignore_odometry", s.ignore_odometry,
    "the log's odometry is not used: every scan is localised as in a log without odometry");
  v("session.motion_search", s.motion_search.enabled,
    "a scan without odometry that the rules do not confirm from the last posture, or only "
    "beyond the minima below, is searched for (wide search) around it over the motion seen "
    "lately, and the correction gate does not apply; off: as a scan with odometry, from the last "
    "posture alone");
  v("session.motion_search_scale", s.motion_search.scale, Bounds{1e-3, 100},
    "... the window: this times the largest motion between consecutive localised scans ...");
  v("session.motion_search_scans", s.motion_search.scans, Bounds{1, 1e5},
    "... over the last this many confirmed ones ...");
  v("session.motion_search_min_m", s.motion_search.min_half_width_m, Bounds{0, 1e3},
    "... at least this half width, m (within recovery's maxima; recovery's minima until 5 "
    "motions are known)");
  v("session.motion_search_min_rad", s.motion_search.min_half_yaw_rad, kAngle,
    "... and at least this half heading range, rad");
  v("session.frozen_odometry_range_change_m", s.motion_search.frozen_odometry_range_change_m,
    Bounds{0, 1e3},
    "while the odometry has not moved since the first scan, a scan whose ranges differ from the "
    "first scan's by more than this (median over the beams) sets the odometry aside until it "
    "moves, m (and localise, holding nothing without odometry, searches again only once the "
    "ranges moved this much since the last search); 0: the odometry is always believed");
}

template <class C, class V>
void VisitLog(C& c, V& v) {
  v("log.max_range_m", c.log.max_range_m, Bounds{1e-3, 1e4},
    "CARMEN FLASER readings at or beyond this are no-return values (with log.no_return_m or "
    "the recognised code, the lower one stands), m");
  v("log.no_return_m", c.log.no_return_m, Bounds{1e-3, 1e4},
    "the log's no-return value by hand: readings at or beyond it carry no echo, m; null: "
    "recognised from the log (log.detect_no_return)");
  v("log.detect_no_return", c.log.detect_no_return,
    "recognise the log's saturation code (a maximum reading repeated over many beams) from its "
    "first scans and treat readings at or beyond it as no-return");
  v("log.laser_offset_m", c.log.laser_offset_m, Bounds{-100, 100},
    "laser distance ahead of the robot base, m; null: the log's PARAM robot_frontlaser_offset");
  v("log.repair_reversed_odometry", c.log.repair_reversed_odometry,
    "reverse odometry increments that move forward while ODOM reports a negative velocity");
}

template <class C, class V>
void VisitOccupancyGrid(C& c, V& v) {
  v("occupancy_grid.write", c.write_occupancy_grid,
    "a session writes map.pgm + map.yaml (map_server) from its validated scans into the run "
    "folder");
  v("occupancy_grid.resolution_m", c.occupancy_grid.resolution_m, Bounds{1e-3, 100},
    "the grid's cell side, m");
}

template <class C, class V>
void VisitRecovery(C& c, V& v) {
  auto& r = c.session.recovery;
  v("recovery.lost_after_unconfirmed", r.lost_after_unconfirmed, Bounds{0, 1e6},
    "localised scans in a row not confirmed before the session is lost and searches wide; 0: "
    "never");
  v("recovery.min_half_width_m", r.min_half_width_m, Bounds{0, 1e3},
    "wide search: the window's half width at least, m ...");
  v("recovery.translation_error_per_m", r.translation_error_per_m, Bounds{0, 10},
    "... plus this per metre driven since the last confirmed scan ...");
  v("recovery.max_half_width_m", r.max_half_width_m, Bounds{0, 1e3}, "... at most this, m");
  v("recovery.min_half_yaw_rad", r.min_half_yaw_rad, kAngle,
    "wide search: the headings within ± this at least, rad ...");
  v("recovery.heading_error_per_rad", r.heading_error_per_rad, Bounds{0, 10},
    "... plus this per radian turned since the last confirmed scan ...");
  v("recovery.heading_error_per_m", r.heading_error_per_m, Bounds{0, 10},
    "... plus this (rad) per metre driven ...");
  v("recovery.max_half_yaw_rad", r.max_half_yaw_rad, kAngle, "... at most this, rad");
  auto& w = r.search;
  v("recovery.search_resolution_m", w.field.resolution_m, Bounds{1e-3, 10},
    "wide search: the likelihood field's cell, m");
  v("recovery.search_sigma_m", w.field.sigma_m, Bounds{1e-3, 10},
    "wide search: the field's σ around each map point, m");
  v("recovery.search_candidates", w.max_candidates, Bounds{1, 1000},
    "wide search: distinct postures handed to the Likelihood Test");
  v("recovery.search_max_beams", w.max_beams, Bounds{1, 1e5},
    "wide search: valid beams scored, evenly subsampled");
  v("recovery.search_min_heading_step_rad", w.min_heading_step_rad, Bounds{1e-4, 0.5},
    "wide search: headings at least this far apart, rad");
}

template <class C, class V>
void VisitLoopClosure(C& c, V& v) {
  auto& l = c.session.loop_closure;
  v("loop_closure.enabled", l.enabled,
    "scans that extend the map become pose graph nodes; closures with old nodes correct them and "
    "the map");
  v("loop_closure.min_path_m", l.min_path_m, Bounds{0, 1e6},
    "a node may close a loop once the path driven since it exceeds this, m");
  v("loop_closure.local_map_radius_m", l.local_map_radius_m, Bounds{1e-3, 1e3},
    "old nodes within this of the current posture render the map a closure is matched on, m");
  v("loop_closure.min_local_nodes", l.min_local_nodes, Bounds{1, 1e6},
    "old nodes needed near before a closure is tried");
  v("loop_closure.max_local_nodes", l.max_local_nodes, Bounds{1, 1e6},
    "... the nearest of them and the nodes laid just before and after it, at most this many");
  v("loop_closure.attempt_every_nodes", l.attempt_every_nodes, Bounds{1, 1e6},
    "a closure is tried once this many new nodes were laid since the last attempt ...");
  v("loop_closure.attempt_every_m", l.attempt_every_m, Bounds{0, 1e6},
    "... and this much path driven since it, m");
  v("loop_closure.min_half_width_m", l.min_half_width_m, Bounds{0, 1e3},
    "closure search: the window's half width at least, m ...");
  v("loop_closure.translation_error_per_m", l.translation_error_per_m, Bounds{0, 10},
    "... plus this per metre driven since the old node ...");
  v("loop_closure.max_half_width_m", l.max_half_width_m, Bounds{0, 1e3}, "... at most this, m");
  v("loop_closure.min_half_yaw_rad", l.min_half_yaw_rad, kAngle,
    "closure search: headings within ± this at least, rad ...");
  v("loop_closure.heading_error_per_m", l.heading_error_per_m, Bounds{0, 10},
    "... plus this (rad) per metre driven since the old node ...");
  v("loop_closure.max_half_yaw_rad", l.max_half_yaw_rad, kAngle, "... at most this, rad");
  v("loop_closure.window_sigmas", l.window_sigmas, Bounds{0, 100},
    "closure search: with > 0, the window spans this many σ of the graph's uncertainty since the "
    "old node instead (minima above hold, beyond the maxima nothing is searched)");
  v("loop_closure.max_sigma_m", l.max_sigma_m, Bounds{1e-6, 1e3},
    "an accepted closure's refinement pins the position to this standard deviation, m");
  v("loop_closure.distinct_m", l.distinct_m, Bounds{0, 1e3},
    "another valid posture this far from a closure's makes it ambiguous, m ...");
  v("loop_closure.distinct_rad", l.distinct_rad, kAngle, "... or this, rad");
  v("loop_closure.confirm_after", l.confirm_after, Bounds{1, 1e6},
    "consecutive nodes whose closures agree on one correction before it is applied");
  v("loop_closure.agree_m", l.agree_m, Bounds{0, 1e3},
    "closures agree when their corrections differ by at most this, m ...");
  v("loop_closure.agree_rad", l.agree_rad, kAngle, "... and this, rad");
  v("loop_closure.confirm_from_run", l.confirm_from_run,
    "the scans between a run's first and last search only the smallest window, around where "
    "the run puts them (the first and last search the whole window)");
  v("loop_closure.set_aside_whole_batch", l.set_aside_whole_batch,
    "when the solve sets aside an edge of a batch of agreeing closures, the graph is solved again "
    "from where it stood: with the batch but without its odometry lesson when its closure missed "
    "the odometry chain by more than the matched one and agree_m, else (or then too) without it");
  v("loop_closure.sigma_floor_m", l.sigma_floor_m, Bounds{1e-6, 1e3},
    "added to the refinement's position σ in the graph's edges, m ...");
  v("loop_closure.sigma_floor_rad", l.sigma_floor_rad, Bounds{1e-6, 10}, "... heading σ, rad");
  v("loop_closure.huber_scale", l.graph.closure_loss_scale, Bounds{0, 1e6},
    "closures pull with a bounded force beyond this many σ (0: plain least squares)");
  v("loop_closure.odometry_edges", l.odometry_edges,
    "consecutive nodes are linked by the odometry too, weighed by how far the odometry and the "
    "matched chain missed the closures confirmed so far (the odometry learned per log)");
  v("loop_closure.odometry_turn_weight_m_per_rad", l.odometry.turn_weight_m_per_rad, Bounds{0, 1e3},
    "odometry model: a radian of turn weighs on the heading like this many metres");
  v("loop_closure.odometry_stretch_m", l.odometry.stretch_m, Bounds{1e-3, 1e6},
    "odometry model: its noise is fitted on stretches of this much path and of 2, 4 and 8 times "
    "it, m");
  v("loop_closure.odometry_position_per_heading_m2", l.odometry.position_per_heading_m2,
    Bounds{0, 1e3},
    "odometry model: its position variance per metre is at least this times its heading's, m²");
  v("loop_closure.odometry_heading_test_chi2", l.odometry.heading_test_chi2, Bounds{0, 1e6},
    "odometry model: its heading noise is zero unless fitting it gains twice the log-likelihood "
    "beyond this χ² (1 dof; 10.828: 99.9 %; 0: no test)");
  v("loop_closure.odometry_position_test_chi2", l.odometry.position_test_chi2, Bounds{0, 1e6},
    "... and its position noise only what its heading noise implies unless fitting more gains "
    "this (0: no test)");
  v("loop_closure.odometry_floor_m", l.odometry.floor_m, Bounds{1e-9, 10},
    "odometry model: added to each step's position σ, m ...");
  v("loop_closure.odometry_floor_rad", l.odometry.floor_rad, Bounds{1e-9, 1},
    "... and heading σ, rad");
  v("loop_closure.rejection_chi2", l.graph.closure_rejection_chi2, Bounds{0, 1e12},
    "a closure whose χ² (3 dof) stays above this after a solve is set aside (0: never)");
  v("loop_closure.render_min_shift_m", l.render_min_shift_m, Bounds{0, 1e3},
    "the map is rendered again when a solve moved a node more than this; a closure predicted "
    "to move less joins the graph unsolved until a larger one or the run's end, m");
  v("loop_closure.tracking_path_m", l.tracking_path_m, Bounds{0, 1e6},
    "the session tracks against the nodes laid within this path (up to twice it), 0: all, m ...");
  v("loop_closure.tracking_min_nodes", l.tracking_min_nodes, Bounds{0, 1e6},
    "... and at least this many newest nodes");
  v("loop_closure.spread_over_unconfirmed", l.spread_over_unconfirmed,
    "in the corrected trajectory the unconfirmed scans, as the skipped ones, take a share (by "
    "time) of the correction the next confirmed scan made to its prediction");
  v("loop_closure.dispute_turn_of_bound", l.dispute_turn_of_bound, Bounds{0, 100},
    "a heading correction beyond this fraction of the correction gate's bound is withdrawn when "
    "the closure tried at the same scan (validated, pending) holds the prediction's heading "
    "within agree_rad and the correction's beyond it: the scan takes the prediction (0: off)");
  v("loop_closure.final_match", l.final_match.enabled,
    "at the end of a run the nodes are matched once more on the whole map rendered from the "
    "solved graph, and the graph solved again with the validated matches in it");
  v("loop_closure.final_match_spacing_m", l.final_match.spacing_m, Bounds{0, 1e6},
    "... one node per this much path, m (0: every node)");
  v("loop_closure.final_match_neighbour_sigmas", l.final_match.neighbour_sigmas, Bounds{0, 1e6},
    "... a node whose heading stands out from where both neighbours put it by the odometry by "
    "more than this many robust σ is refined from there too, the best validated match kept "
    "(0: never; 3 measured)");
}

template <class C, class V>
void VisitLocalise(C& c, V& v) {
  auto& l = c.localise;
  v("localise.confirm_after", l.confirm_after, Bounds{1, 1e6},
    "scans in a row the rules must validate the only hypothesis left before it is confirmed");
  v("localise.research_distance_m", l.research_distance_m, Bounds{0, 1e3},
    "until a posture is confirmed (and while no hypothesis is held), the map is searched again "
    "after the odometry moved this far, m ...");
  v("localise.research_turn_rad", l.research_turn_rad, Bounds{0, 2 * M_PI},
    "... or turned this, rad");
  v("localise.drop_after_unconfirmed", l.drop_after_unconfirmed, Bounds{1, 1e6},
    "a hypothesis not yet confirmed is dropped after this many unconfirmed scans in a row");
  v("localise.lost_after_unconfirmed", l.lost_after_unconfirmed, Bounds{1, 1e6},
    "a confirmed posture is lost (the global search starts again) after this many");
  v("localise.min_cost_excess_ratio", l.min_cost_excess_ratio, Bounds{0, 1e3},
    "a hypothesis costlier than another at the same scans beyond chance is dropped when the "
    "excess is at least this fraction of the cheaper's cost");
  v("localise.map_signature", l.map_signature,
    "rule 2's prior E_max is the point map's own signature (summary.json beside the PCD), when "
    "a session wrote one");
  v("localise.place_bound", l.place_bound,
    "... raised at each place by how much worse than the map's median its nearest sampled "
    "scans fit");
  v("localise.track_while_still", l.track_while_still,
    "until a posture is confirmed, every scan is localised, even while the robot stands still");
  v("localise.relative_cost_needs_truncated_mean", l.relative_cost_needs_truncated_mean,
    "a hypothesis rule 3 rejects against the cheapest held one counts towards its discarding "
    "only when its truncated mean distance is above that one's too");
  v("localise.drop_outmatched", l.drop_outmatched,
    "a hypothesis goes once another matched its pairs tighter beyond chance, by "
    "min_cost_excess_ratio at least, with a lower truncated mean on average");
  v("localise.steady_output", l.steady_output,
    "while ambiguous, the output stays with the hypothesis it followed until that one fails the "
    "rules or another costs min_cost_excess_ratio less at the same scans");
  v("localise.scan_odometry", l.scan_odometry,
    "without the log's odometry (none, ignored or frozen), each scan's match on the scan before "
    "carries the hypotheses as an odometry would");
  v("localise.max_hypotheses", l.max_hypotheses, Bounds{1, 1000}, "hypotheses held at most");
  v("localise.same_posture_m", l.same_posture_m, Bounds{0, 1e3},
    "hypotheses closer than this and same_posture_rad are one, m");
  v("localise.same_posture_rad", l.same_posture_rad, kAngle, "... and this, rad");
  v("localise.evidence_from_new_views", l.evidence_from_new_views,
    "a scan's costs tell held hypotheses apart only when it is a new view: the odometry moved "
    "or turned as much since the last scan whose costs did as the session's insert gate asks");
  auto& w = l.search;
  v("localise.search_resolution_m", w.field.resolution_m, Bounds{1e-3, 10},
    "global search: the likelihood field's cell, m");
  v("localise.search_sigma_m", w.field.sigma_m, Bounds{1e-3, 10},
    "global search: the field's σ around each map point, m");
  v("localise.search_levels", w.field.levels, Bounds{1, 16},
    "global search: branch-and-bound levels (top blocks of 2^(levels−1) cells)");
  v("localise.search_candidates", w.max_candidates, Bounds{1, 1000},
    "global search: distinct postures refined and tested by the rules");
  v("localise.search_max_beams", w.max_beams, Bounds{1, 1e5},
    "global search: valid beams scored, evenly subsampled");
  v("localise.search_min_heading_step_rad", w.min_heading_step_rad, Bounds{1e-4, 0.5},
    "global search: headings at least this far apart, rad");
  v("localise.search_min_separation_m", w.min_separation_m, Bounds{0, 1e3},
    "global search: distinct postures are this far apart at least, m ...");
  v("localise.search_min_separation_rad", w.min_separation_rad, kAngle, "... or this, rad");
}

// Every option, in the order of the help text.
template <class C, class V>
void VisitOptions(C& c, V& v) {
  VisitScoring(c, v);
  VisitValidation(c, v);
  VisitRefinement(c, v);
  VisitSession(c, v);
  VisitRecovery(c, v);
  VisitLoopClosure(c, v);
  VisitLocalise(c, v);
  VisitLog(c, v);
  VisitOccupancyGrid(c, v);
}

// Keys that no longer exist, with where their meaning went.
struct MovedOption {
  const char* old_key;
  const char* new_key;
};
inline constexpr MovedOption kMovedOptions[] = {
    {"session.max_expect_value_m", "validation.max_expect_value_m"},
    {"refinement.error_descent.alpha_m", "validation.alpha_m"},
};

}  // namespace scanloc::config_table
