#pragma once
// Fixtures of the report tests: a small synthetic session (a walk through the classroom, simulated
// scans, run by `scanloc session`) to report on.

#include <random>
#include <string>
#include <vector>

#include "run_scanloc.hpp"

#include "scanloc/io/sequence_sources.hpp"
#include "scanloc/maps/line_map.hpp"
#include "scanloc/worlds/laser_simulator.hpp"

namespace scanloc::testing {

inline const std::string kClassroomLines =
    std::string(SCANLOC_SOURCE_DIR) + "/datasets/classroom/classroom.lines";

// The report tests' names for the shared runner's (run_scanloc.hpp).
using CommandResult = ScanlocRun;
inline std::string ReadText(const std::string& path) {
  return ReadWholeFile(path);
}

// A walk through the classroom: `scans` scans 6 cm apart along x (heading 0.1 rad, a turn in the
// middle), 720 beams, exact odometry, fixed seed; written as a native sequence.
inline void WriteClassroomWalk(const std::string& path, int scans = 24) {
  const LineMap world = ReadLineMap(kClassroomLines);
  LaserSimulatorOptions laser;
  laser.beam_count = 720;
  std::mt19937 rng(7);
  SequenceFileWriter writer(path, LaserMounting{});
  const Pose2D start{1.5, 3.0, 0.1};
  Pose2D truth = start;
  for (int i = 0; i < scans; ++i) {
    if (i > 0) truth = truth * Pose2D{0.06, 0.0, i == scans / 2 ? 0.3 : 0.0};
    Iteration it;
    it.timestamp_s = 100.0 + 0.5 * i;
    it.scan = SimulateLaser(world, truth, laser, rng);
    it.odometry = start.Inverse() * truth;  // T_odom_robot, the odometry frame at the start
    writer.Write(it, truth);
  }
  writer.Close();
}

// Runs `scanloc session` on a classroom walk with the classroom's line map into dir/run; returns
// the run folder ("" after a failure, which is reported).
inline std::string MakeClassroomRun(const std::string& dir) {
  const std::string sequence = dir + "/walk.seq.jsonl", run = dir + "/run";
  WriteClassroomWalk(sequence);
  const CommandResult r =
      RunScanloc({"session", "--log", sequence, "--line-map", kClassroomLines, "--out", run,
                  "--initial-pose", "1.5", "3.0", "0.1", "--quiet"},
                 dir);
  if (!r.exited || r.exit_code != 0) {
    ADD_FAILURE() << "scanloc session failed: " << r;
    return "";
  }
  return run;
}

}  // namespace scanloc::testing
