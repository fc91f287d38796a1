#pragma once
// The relative-pose metric of Kümmerle et al. 2009 ("On measuring the accuracy of SLAM
// algorithms"): an estimated trajectory scored against ground-truth relations between scans.

#include <cstddef>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/geometry/pose2d.hpp"
#include "scanloc/io/trajectory.hpp"

namespace scanloc {

// The pose of the scan taken at t2 expressed in the frame of the scan taken at t1: relations
// relate the laser's poses, not the robot's (they come from matching scans).
struct Relation {
  double t1_s = 0.0;
  double t2_s = 0.0;
  Pose2D T_1_2;
};

// Reads `t1 t2 x y z roll pitch yaw` lines; z, roll and pitch must be zero (planar relations).
// Throws ParseError naming file and line for a malformed line, std::runtime_error when the file
// cannot be opened.
std::vector<Relation> ReadRelations(const std::string& path);

struct RelationsEvaluationOptions {
  // A relation's timestamp matches the trajectory's nearest timestamp when they differ by at most
  // this. Seconds, >= 0.
  double timestamp_tolerance_s = 1e-3;
};

// Population statistics of one error measure over the matched relations (zero when none matched).
struct ErrorStatistics {
  double mean = 0.0;
  double std = 0.0;
  double max = 0.0;
};

struct RelationsEvaluation {
  std::size_t matched = 0;
  std::size_t unmatched = 0;
  std::vector<Relation> unmatched_relations;  // those with t1 or t2 absent from the trajectory
  std::vector<Pose2D> errors;                 // per matched relation, in the relations' order
  // errors[k] belongs to relations[matched_relations[k]].
  std::vector<std::size_t> matched_relations;
  ErrorStatistics translation_m;           // |t(e)|
  ErrorStatistics rotation_deg;            // |θ(e)|
  ErrorStatistics translation_squared_m2;  // |t(e)|²
  ErrorStatistics rotation_squared_deg2;   // θ(e)²
};

// For each relation δ*, the error e = δ ⊖ δ* = Between(δ*, δ), where δ = Between(est(t1), est(t2))
// is the estimated relative pose and est(t) the trajectory pose whose timestamp is nearest t
// (within the tolerance); relations lacking either pose count as unmatched. The trajectory may be
// in any order. Throws std::invalid_argument for a negative or non-finite tolerance.
RelationsEvaluation EvaluateRelations(const std::vector<StampedPose>& trajectory,
                                      const std::vector<Relation>& relations,
                                      const RelationsEvaluationOptions& options = {});

// For each pair (t1, t2), the trajectory's relative pose Between(est(t1), est(t2)), est as
// above; nothing when either pose is absent. Throws std::invalid_argument as EvaluateRelations.
std::vector<std::optional<Pose2D>> RelativePoses(
    const std::vector<StampedPose>& trajectory, const std::vector<std::pair<double, double>>& pairs,
    const RelationsEvaluationOptions& options = {});

// The laser's poses of a trajectory of the robot's, the laser mounted as `mounting` says: what
// relations between scans are to be compared with. Where the laser sits ahead of the robot's base,
// the robot's relative pose between two passes in opposite directions differs from the scans' by
// twice the offset.
std::vector<StampedPose> LaserPoses(std::vector<StampedPose> robot_poses,
                                    const LaserMounting& mounting);

}  // namespace scanloc
