#include "scanloc/common/atomic_file.hpp"

#include <unistd.h>

#include <atomic>
#include <cstdio>
#include <cstring>
#include <fstream>
#include <stdexcept>

namespace scanloc {

std::string TemporaryPathFor(const std::string& path) {
  static std::atomic<unsigned> counter{0};
  return path + ".tmp-" + std::to_string(::getpid()) + "-" + std::to_string(counter++);
}

void CommitTemporaryFile(const std::string& temporary_path, const std::string& path) {
  if (std::rename(temporary_path.c_str(), path.c_str()) != 0) {
    const std::string reason = std::strerror(errno);
    std::remove(temporary_path.c_str());
    throw std::runtime_error("cannot rename " + temporary_path + " to " + path + ": " + reason);
  }
}

void WriteFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  const std::string temporary = TemporaryPathFor(path);
  {
    std::ofstream out(temporary);
    if (!out)
      throw std::runtime_error("cannot write " + path + " (is its folder there and writable?)");
    try {
      write(out);
    } catch (...) {
      out.close();
      std::remove(temporary.c_str());
      throw;
    }
    out.flush();
    if (!out) {
      out.close();
      std::remove(temporary.c_str());
      throw std::runtime_error("error while writing " + path);
    }
  }
  CommitTemporaryFile(temporary, path);
}

}  // namespace scanloc
