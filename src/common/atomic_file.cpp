#include "scanloc/common/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <memory>
#include <ostream>
#include <stdexcept>
#include <streambuf>
#include <vector>

namespace scanloc {
namespace {

// Bytes gathered before one write(2): large enough that the system calls cost nothing.
constexpr std::size_t kWriteBufferBytes = 1 << 16;

// A stream buffer over a file descriptor with plain write(2) calls (never mmap, whose failure on a
// full disk is a SIGBUS): the first failed write remembers errno and puts the stream in error.
class FileDescriptorBuffer : public std::streambuf {
 public:
  explicit FileDescriptorBuffer(int fd) : fd_(fd), buffer_(kWriteBufferBytes) {
    setp(buffer_.data(), buffer_.data() + buffer_.size());
  }
  // errno of the first failure, 0 when every write succeeded.
  int error() const { return error_; }

 protected:
  int_type overflow(int_type c) override {
    if (!Drain()) return traits_type::eof();
    if (traits_type::eq_int_type(c, traits_type::eof())) return traits_type::not_eof(c);
    *pptr() = traits_type::to_char_type(c);
    pbump(1);
    return c;
  }
  int sync() override { return Drain() ? 0 : -1; }

 private:
  bool Drain() {
    const char* next = pbase();
    while (error_ == 0 && next < pptr()) {
      const ssize_t written = ::write(fd_, next, static_cast<std::size_t>(pptr() - next));
      if (written < 0 && errno == EINTR) continue;
      if (written <= 0) error_ = written < 0 ? errno : EIO;
      if (written > 0) next += written;
    }
    setp(buffer_.data(), buffer_.data() + buffer_.size());
    return error_ == 0;
  }

  int fd_;
  std::vector<char> buffer_;
  int error_ = 0;
};

std::runtime_error WriteError(const std::string& path, int error) {
  return std::runtime_error("cannot write " + path + ": " + std::strerror(error));
}

}  // namespace

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

struct AtomicFileWriter::Impl {
  explicit Impl(const std::string& output_path)
      : path(output_path),
        temporary(TemporaryPathFor(output_path)),
        fd(::open(temporary.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644)),
        buffer(fd),
        out(&buffer) {
    if (fd < 0) throw WriteError(path, errno);
  }
  // Closes and removes the temporary (once).
  void Abandon() {
    if (fd < 0) return;
    ::close(fd);
    fd = -1;
    std::remove(temporary.c_str());
  }

  std::string path, temporary;
  int fd;
  FileDescriptorBuffer buffer;
  std::ostream out;
};

AtomicFileWriter::AtomicFileWriter(const std::string& path) : impl_(std::make_unique<Impl>(path)) {}

AtomicFileWriter::~AtomicFileWriter() {
  impl_->Abandon();
}

std::ostream& AtomicFileWriter::stream() {
  return impl_->out;
}

void AtomicFileWriter::Commit() {
  Impl& f = *impl_;
  if (f.fd < 0) throw std::logic_error("AtomicFileWriter: " + f.path + " committed twice");
  f.out.flush();
  int error = f.buffer.error();
  if (error == 0 && !f.out) error = EIO;
  // The data is on disk before the rename makes it the file: a crash leaves old or new, not empty.
  if (error == 0 && ::fsync(f.fd) != 0) error = errno;
  if (error != 0) {
    f.Abandon();
    throw WriteError(f.path, error);
  }
  const int fd = f.fd;
  f.fd = -1;
  if (::close(fd) != 0) {
    error = errno;
    std::remove(f.temporary.c_str());
    throw WriteError(f.path, error);
  }
  CommitTemporaryFile(f.temporary, f.path);
}

void WriteFileAtomically(const std::string& path, const std::function<void(std::ostream&)>& write) {
  AtomicFileWriter file(path);
  write(file.stream());  // an exception abandons the temporary
  file.Commit();
}

}  // namespace scanloc
