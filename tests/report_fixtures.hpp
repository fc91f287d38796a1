#pragma once
// Fixtures of the report tests: running the scanloc executable, and a small synthetic session
// (a walk through the classroom, simulated scans, run by `scanloc session`) to report on.

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <iterator>
#include <ostream>
#include <random>
#include <string>
#include <vector>

#include "scanloc/io/sequence_sources.hpp"
#include "scanloc/maps/line_map.hpp"
#include "scanloc/simulation/laser_simulator.hpp"

extern char** environ;

namespace scanloc::testing {

inline const std::string kClassroomLines =
    std::string(SCANLOC_SOURCE_DIR) + "/datasets/classroom/classroom.lines";

inline std::string ReadText(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct CommandResult {
  bool exited = false;  // ended through exit(), not killed by a signal
  int exit_code = -1;
  std::string out, err;
};

inline std::ostream& operator<<(std::ostream& os, const CommandResult& r) {
  return os << (r.exited ? "exit " + std::to_string(r.exit_code) : std::string("killed"))
            << "\n--- stdout ---\n"
            << r.out << "--- stderr ---\n"
            << r.err;
}

// Runs `words` (argv[0] looked up in PATH, no shell) with stdout and stderr captured in files of
// `dir`.
inline CommandResult RunCommand(std::vector<std::string> words, const std::string& dir) {
  const std::string out_path = dir + "/command-stdout.txt", err_path = dir + "/command-stderr.txt";
  std::vector<char*> argv;
  for (auto& word : words) argv.push_back(word.data());
  argv.push_back(nullptr);
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_addopen(&actions, STDOUT_FILENO, out_path.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_addopen(&actions, STDERR_FILENO, err_path.c_str(),
                                   O_WRONLY | O_CREAT | O_TRUNC, 0644);
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, argv[0], &actions, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&actions);
  CommandResult result;
  if (spawned != 0) {
    result.err = "cannot start " + words[0];
    return result;
  }
  int status = 0;
  waitpid(pid, &status, 0);
  result.exited = WIFEXITED(status);
  result.exit_code = result.exited ? WEXITSTATUS(status) : -1;
  result.out = ReadText(out_path);
  result.err = ReadText(err_path);
  return result;
}

// The scanloc executable with `arguments`.
inline CommandResult RunScanloc(std::vector<std::string> arguments, const std::string& dir) {
  arguments.insert(arguments.begin(), SCANLOC_BINARY);
  return RunCommand(std::move(arguments), dir);
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
