#pragma once
// scanloc evaluate --closures: how many of a session's loop closures were right, against
// reference poses of the log.

#include <string>
#include <vector>

namespace scanloc::app {

struct ClosureEvaluationArguments {
  std::string run_folder;                         // a session's, run with loop closure on
  std::string reference_path;                     // `t x y θ` (corrected poses) or TUM
  double tolerance_s = 1e-3;                      // timestamp matching
  double max_error_m = 0.1, max_error_deg = 1.0;  // a closure within both is right
  bool json = false;
  std::vector<double> mounting;  // x y yaw of the laser on the robot; empty: the run's
};

// The reference poses are the scans'; they are compared with the closures, which relate the
// robot's postures, through the laser's mounting (ResolveEvaluationFrame). Prints the counts, the
// share right and the errors (text or JSON). Throws std::runtime_error when the run tried no
// closure, measured none, or no measured closure has reference poses.
void EvaluateRunClosures(const ClosureEvaluationArguments& arguments);

}  // namespace scanloc::app
