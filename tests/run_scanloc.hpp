#pragma once
// Runs the scanloc executable (SCANLOC_BINARY), or another program, without a shell, capturing
// stdout and stderr.

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <fstream>
#include <iterator>
#include <ostream>
#include <string>
#include <vector>

extern char** environ;

namespace scanloc::testing {

inline std::string ReadWholeFile(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

struct ScanlocRun {
  bool exited = false;  // ended through exit(), not killed by a signal
  int exit_code = -1;   // valid when exited
  int signal = 0;       // the signal that ended it, when not exited
  std::string out, err;
};

inline std::ostream& operator<<(std::ostream& os, const ScanlocRun& r) {
  return os << (r.exited ? "exit " + std::to_string(r.exit_code)
                         : "killed by signal " + std::to_string(r.signal))
            << "\n--- stdout ---\n"
            << r.out << "--- stderr ---\n"
            << r.err;
}

// Runs `words` (argv[0] looked up in PATH, no shell) with stdout and stderr captured in files of
// `scratch_dir`.
inline ScanlocRun RunCommand(std::vector<std::string> words, const std::string& scratch_dir) {
  const std::string out_path = scratch_dir + "/stdout.txt", err_path = scratch_dir + "/stderr.txt";
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
  ScanlocRun result;
  if (spawned != 0) {
    result.err = "cannot start " + words[0];
    return result;
  }
  int status = 0;
  waitpid(pid, &status, 0);
  result.exited = WIFEXITED(status);
  result.exit_code = result.exited ? WEXITSTATUS(status) : -1;
  result.signal = WIFSIGNALED(status) ? WTERMSIG(status) : 0;
  result.out = ReadWholeFile(out_path);
  result.err = ReadWholeFile(err_path);
  return result;
}

// The scanloc executable (SCANLOC_BINARY) with `arguments`; `scratch_dir` receives the streams.
inline ScanlocRun RunScanloc(std::vector<std::string> arguments, const std::string& scratch_dir) {
  arguments.insert(arguments.begin(), SCANLOC_BINARY);
  return RunCommand(std::move(arguments), scratch_dir);
}

}  // namespace scanloc::testing
