#pragma once
// What every fuzz target shares: the input written to a file (the readers take paths), the
// errors a reader may throw for bad input, and a check that aborts when a reader's result breaks
// its contract. Anything else that escapes a harness (another exception, a sanitizer report, an
// abort) is a finding.

#include <unistd.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <stdexcept>
#include <string>

#include "scanloc/common/parse_error.hpp"
#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/geometry/pose2d.hpp"

namespace scanloc::fuzz {

// A file of this process, rewritten for every input and removed at exit. In /dev/shm when it is
// writable (no disk traffic), else in $TMPDIR or /tmp; $SCANLOC_FUZZ_TMPDIR overrides.
class InputFile {
 public:
  explicit InputFile(const std::string& suffix)
      : path_(Directory() + "/scanloc-fuzz-" + std::to_string(::getpid()) + suffix) {}
  ~InputFile() { std::remove(path_.c_str()); }
  InputFile(const InputFile&) = delete;
  InputFile& operator=(const InputFile&) = delete;

  const std::string& Write(const std::uint8_t* data, std::size_t size) const {
    std::FILE* file = std::fopen(path_.c_str(), "wb");
    if (file == nullptr || std::fwrite(data, 1, size, file) != size || std::fclose(file) != 0) {
      std::perror(path_.c_str());
      std::abort();  // the harness, not the reader, failed
    }
    return path_;
  }
  const std::string& path() const { return path_; }

 private:
  static std::string Directory() {
    if (const char* dir = std::getenv("SCANLOC_FUZZ_TMPDIR")) return dir;
    if (::access("/dev/shm", W_OK) == 0) return "/dev/shm";
    if (const char* dir = std::getenv("TMPDIR")) return dir;
    return "/tmp";
  }
  std::string path_;
};

// Runs `read`, accepting the errors the readers document for bad input: ParseError (a
// std::runtime_error), other std::runtime_error and std::invalid_argument.
template <class Read>
void AcceptDocumentedErrors(const Read& read) {
  try {
    read();
  } catch (const std::runtime_error&) {
  } catch (const std::invalid_argument&) {
  }
}

// Aborts with a message when a reader returned something that breaks its contract.
inline void Require(bool holds, const std::string& what) {
  if (holds) return;
  std::fprintf(stderr, "scanloc fuzz: contract broken: %s\n", what.c_str());
  std::abort();
}

// Every coordinate of a posture a reader returns is finite.
inline bool FinitePose(const Pose2D& pose) {
  return std::isfinite(pose.x_m) && std::isfinite(pose.y_m) && std::isfinite(pose.yaw_rad);
}

// A scan a reader returns must be one the rest of the library accepts.
inline void RequireConsistentScan(const LaserScan& scan) {
  try {
    scan.CheckConsistent();
  } catch (const std::invalid_argument& error) {
    std::fprintf(stderr, "scanloc fuzz: a reader returned an inconsistent scan: %s\n",
                 error.what());
    std::abort();
  }
}

}  // namespace scanloc::fuzz
