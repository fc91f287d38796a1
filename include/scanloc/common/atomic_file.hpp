#pragma once
// Output files are written whole or not at all: to a temporary sibling, then renamed.

#include <functional>
#include <iosfwd>
#include <memory>
#include <string>

namespace scanloc {

// Calls `write` on a stream to `path`.tmp-XXXX (plain write(2) calls, no mmap), fsyncs it and
// renames it over `path`. When a write, the fsync or the rename fails (a full disk, say) it removes
// the temporary and throws std::runtime_error naming `path` and the system's reason (strerror).
void WriteFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write);

// An output written over time (a sequence, one record after another) to a temporary sibling of
// `path` with plain write(2) calls; Commit() syncs it and renames it over `path`. Destroyed without
// Commit() (abandoned, or after an error), it removes the temporary. Errors are std::runtime_error
// naming `path` and the system's reason.
class AtomicFileWriter {
 public:
  explicit AtomicFileWriter(const std::string& path);
  ~AtomicFileWriter();
  AtomicFileWriter(const AtomicFileWriter&) = delete;
  AtomicFileWriter& operator=(const AtomicFileWriter&) = delete;
  std::ostream& stream();
  void Commit();

 private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
};

// Renames `temporary_path` over `path`, throwing std::runtime_error with both names on failure.
void CommitTemporaryFile(const std::string& temporary_path, const std::string& path);

// A unique temporary path beside `path`.
std::string TemporaryPathFor(const std::string& path);

}  // namespace scanloc
