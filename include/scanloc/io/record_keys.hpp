#pragma once
// The iteration record's file format, defined once: every JSON key of a line of iterations.jsonl
// (and of the candidate reports of `scanloc test --json` and `refine --json`, which share its
// objects). The writer (run_folder, candidate_report) and the report's reader (run_records) both
// spell the keys through these names, so the two cannot drift apart.

namespace scanloc::record_keys {

inline constexpr const char* kBest = "best";
inline constexpr const char* kCandidate = "candidate";
inline constexpr const char* kCandidates = "candidates";
inline constexpr const char* kCarved = "carved";
inline constexpr const char* kCentre = "centre";
inline constexpr const char* kChosen = "chosen";
inline constexpr const char* kConverged = "converged";
inline constexpr const char* kCorrectionFromPredictionMmMmMrad =
    "correction_from_prediction_mm_mm_mrad";
inline constexpr const char* kCorrectionMmMmMrad = "correction_mm_mm_mrad";
inline constexpr const char* kCost = "cost";
inline constexpr const char* kCostM2 = "cost_m2";
inline constexpr const char* kCovariance = "covariance";
inline constexpr const char* kDegeneracy = "degeneracy";
inline constexpr const char* kDegenerate = "degenerate";
inline constexpr const char* kDispersionM2 = "dispersion_m2";
inline constexpr const char* kEvaluate = "evaluate";
inline constexpr const char* kExpectValueM = "expect_value_m";
inline constexpr const char* kFirst = "first";
inline constexpr const char* kFound = "found";
inline constexpr const char* kHalfWidthM = "half_width_m";
inline constexpr const char* kHalfYawRad = "half_yaw_rad";
inline constexpr const char* kHeadings = "headings";
inline constexpr const char* kFlagged = "flagged";
inline constexpr const char* kHistogram = "histogram";
inline constexpr const char* kHypotheses = "hypotheses";
inline constexpr const char* kDiscarded = "discarded";
inline constexpr const char* kConfirmedInRow = "confirmed_in_row";
inline constexpr const char* kUnconfirmedInRow = "unconfirmed_in_row";
inline constexpr const char* kConfirmations = "confirmations";
inline constexpr const char* kSearches = "searches";
inline constexpr const char* kHeld = "held";
inline constexpr const char* kState = "state";
inline constexpr const char* kPosed = "posed";
inline constexpr const char* kIndex = "index";
inline constexpr const char* kInitialTWorldRobot = "initial_T_world_robot";
inline constexpr const char* kInsert = "insert";
inline constexpr const char* kInserted = "inserted";
inline constexpr const char* kNewGround = "new_ground";
inline constexpr const char* kIterations = "iterations";
inline constexpr const char* kLabel = "label";
inline constexpr const char* kLost = "lost";
inline constexpr const char* kLikelihoodDistance = "likelihood_distance";
inline constexpr const char* kLikelihoodDistanceAfter = "likelihood_distance_after";
inline constexpr const char* kLikelihoodDistanceBefore = "likelihood_distance_before";
inline constexpr const char* kLikelihoodTest = "likelihood_test";
inline constexpr const char* kLikelihoodTestAfter = "likelihood_test_after";
inline constexpr const char* kLikelihoodTestBefore = "likelihood_test_before";
inline constexpr const char* kMapPoints = "map_points";
inline constexpr const char* kMatchPairs = "match_pairs";
inline constexpr const char* kMaxExpectValueM = "max_expect_value_m";
inline constexpr const char* kMatchRatio = "match_ratio";
inline constexpr const char* kNodesScored = "nodes_scored";
inline constexpr const char* kOrigin = "origin";
inline constexpr const char* kPrediction = "prediction";
inline constexpr const char* kProblems = "problems";
inline constexpr const char* kRank = "rank";
inline constexpr const char* kReason = "reason";
inline constexpr const char* kRecovered = "recovered";
inline constexpr const char* kMotionSearch = "motion_search";
inline constexpr const char* kOdometryFrozen = "odometry_frozen";
inline constexpr const char* kWithoutOdometry = "without_odometry";
inline constexpr const char* kOdometryFromScans = "odometry_from_scans";
inline constexpr const char* kMotionSearchedHypotheses = "motion_searched_hypotheses";
inline constexpr const char* kEvidence = "evidence";
inline constexpr const char* kRefine = "refine";
inline constexpr const char* kRefinedCandidates = "refined_candidates";
inline constexpr const char* kRefinedTWorldRobot = "refined_T_world_robot";
inline constexpr const char* kRefinement = "refinement";
inline constexpr const char* kSearch = "search";
// A loop closure tried (IterationRecord::closure).
inline constexpr const char* kClosure = "closure";
inline constexpr const char* kAccepted = "accepted";
inline constexpr const char* kNode = "node";
inline constexpr const char* kOldNode = "old_node";
inline constexpr const char* kOldIteration = "old_iteration";
inline constexpr const char* kLocalNodes = "local_nodes";
inline constexpr const char* kPathSinceM = "path_since_m";
inline constexpr const char* kChainSigmaM = "chain_sigma_m";
inline constexpr const char* kChainSigmaRad = "chain_sigma_rad";
inline constexpr const char* kMatched = "T_world_robot_matched";
inline constexpr const char* kTOldRobot = "T_old_robot";
inline constexpr const char* kPredictedShiftM = "predicted_shift_m";
inline constexpr const char* kSolveDeferred = "solve_deferred";
inline constexpr const char* kFromRun = "from_run";
inline constexpr const char* kSolveIterations = "solve_iterations";
inline constexpr const char* kLargestShiftM = "largest_shift_m";
inline constexpr const char* kRendered = "rendered";
inline constexpr const char* kSignatureExpectValueM = "signature_expect_value_m";
inline constexpr const char* kCorrectionBound = "correction_bound_m_rad";
inline constexpr const char* kBeyondOdometry = "beyond_odometry";
inline constexpr const char* kSlideRefused = "slide_refused";
inline constexpr const char* kCorrectionSum = "correction_sum_before_after_bound_m";
inline constexpr const char* kTurnDisputed = "turn_disputed_by_closure";
inline constexpr const char* kOutrankedRefinement = "outranked_refinement";
inline constexpr const char* kTracked = "T_world_robot_tracked";
inline constexpr const char* kCorrectionRad = "correction_rad";
inline constexpr const char* kClosureFromPredictionRad = "closure_from_prediction_rad";
inline constexpr const char* kClosureFromTrackedRad = "closure_from_tracked_rad";
inline constexpr const char* kSkipped = "skipped";
inline constexpr const char* kSqrtDispersionM = "sqrt_dispersion_m";
inline constexpr const char* kTWorldLaser = "T_world_laser";
inline constexpr const char* kTruncatedMeanM = "truncated_mean_m";
inline constexpr const char* kTWorldRobot = "T_world_robot";
inline constexpr const char* kTimeS = "time_s";
inline constexpr const char* kTimestampS = "timestamp_s";
inline constexpr const char* kTimingsMs = "timings_ms";
inline constexpr const char* kTotal = "total";
inline constexpr const char* kValid = "valid";
inline constexpr const char* kValidPairs = "valid_pairs";
inline constexpr const char* kValidated = "validated";
inline constexpr const char* kWeightedPairs = "weighted_pairs";
inline constexpr const char* kXM = "x_m";
inline constexpr const char* kYM = "y_m";
inline constexpr const char* kYawRad = "yaw_rad";

}  // namespace scanloc::record_keys
