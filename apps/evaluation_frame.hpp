#pragma once
// The frame `scanloc evaluate` scores in. Relations and reference poses are the scans' (a relation
// is the pose of one scan in the frame of another); a session's trajectories are the robot's. The
// laser's mounting turns one into the other.

#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "scanloc/geometry/laser_scan.hpp"

namespace scanloc::app {

struct EvaluationFrame {
  LaserMounting mounting;  // the laser on the robot whose postures are scored
  std::string source;      // where the mounting came from, for the reader
};

// `given` (x y yaw from --mounting) when it is not empty; else the mounting recorded in
// `run_folder`/summary.json; else none (the postures are taken as the scans' own, and a note on
// standard error says so). Throws std::runtime_error for a given mounting that is not finite, and
// naming the file when summary.json is unreadable.
EvaluationFrame ResolveEvaluationFrame(const std::vector<double>& given,
                                       const std::string& run_folder);

// "laser at (0.040, 0.000) m, 0.000 rad on the robot, from …", for text output.
std::string Describe(const EvaluationFrame& frame);
nlohmann::json ToJson(const EvaluationFrame& frame);

}  // namespace scanloc::app
