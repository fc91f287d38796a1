// Output files are whole or absent: a write that fails (a full disk, here a file-size limit) is an
// error naming the file and the system's reason, and leaves no temporary behind.

#include "scanloc/common/atomic_file.hpp"

#include <gtest/gtest.h>
#include <sys/resource.h>

#include <csignal>
#include <filesystem>
#include <ostream>
#include <stdexcept>
#include <string>

#include "run_scanloc.hpp"
#include "scanloc/maps/point_map.hpp"
#include "scanloc/maps/point_map_io.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

namespace fs = std::filesystem;

// While alive, files of this process may not grow beyond `bytes` (writes beyond fail with EFBIG, as
// on a full disk, rather than raising SIGXFSZ).
class FileSizeLimit {
 public:
  explicit FileSizeLimit(rlim_t bytes) {
    getrlimit(RLIMIT_FSIZE, &saved_);
    previous_handler_ = std::signal(SIGXFSZ, SIG_IGN);
    rlimit limit = saved_;
    limit.rlim_cur = bytes;
    setrlimit(RLIMIT_FSIZE, &limit);
  }
  ~FileSizeLimit() {
    setrlimit(RLIMIT_FSIZE, &saved_);
    std::signal(SIGXFSZ, previous_handler_);
  }
  FileSizeLimit(const FileSizeLimit&) = delete;
  FileSizeLimit& operator=(const FileSizeLimit&) = delete;

 private:
  rlimit saved_{};
  void (*previous_handler_)(int) = nullptr;
};

class AtomicFileTest : public testing::TemporaryDirTest {
 protected:
  std::size_t EntriesInDir() const {
    return static_cast<std::size_t>(
        std::distance(fs::directory_iterator(dir_), fs::directory_iterator()));
  }
};

// Expects `call` to throw std::runtime_error whose message contains every one of `parts`.
template <class Call>
void ExpectRuntimeErrorWith(Call call, const std::vector<std::string>& parts) {
  try {
    call();
    ADD_FAILURE() << "no exception";
  } catch (const std::runtime_error& error) {
    for (const std::string& part : parts)
      EXPECT_NE(std::string(error.what()).find(part), std::string::npos)
          << "'" << part << "' not in: " << error.what();
  }
}

TEST_F(AtomicFileTest, WritesTheWholeContentAndNothingElse) {
  const std::string path = dir_ + "/out.txt";
  WriteFileAtomically(path, [](std::ostream& out) { out << std::string(200000, 'x') << "end\n"; });
  EXPECT_EQ(testing::ReadWholeFile(path), std::string(200000, 'x') + "end\n");
  EXPECT_EQ(EntriesInDir(), 1u);
}

TEST_F(AtomicFileTest, WriteFailureNamesThePathAndReasonAndLeavesNoTemporary) {
  const std::string path = dir_ + "/big.txt";
  {
    const FileSizeLimit limit(64 * 1024);
    ExpectRuntimeErrorWith(
        [&] {
          WriteFileAtomically(path, [](std::ostream& out) { out << std::string(1 << 20, 'x'); });
        },
        {path, "File too large"});
  }
  EXPECT_EQ(EntriesInDir(), 0u) << "neither the file nor its temporary";
}

TEST_F(AtomicFileTest, StreamedWriterLeavesNothingWhenAbandonedAndReportsAFailedWriteAtCommit) {
  {
    AtomicFileWriter abandoned(dir_ + "/abandoned.txt");
    abandoned.stream() << "half a file";
  }
  EXPECT_EQ(EntriesInDir(), 0u);
  const std::string path = dir_ + "/records.jsonl";
  {
    const FileSizeLimit limit(64 * 1024);
    AtomicFileWriter file(path);
    for (int i = 0; i < 10000; ++i) file.stream() << "{\"record\": " << i << "}\n";
    ExpectRuntimeErrorWith([&] { file.Commit(); }, {path, "File too large"});
  }
  EXPECT_EQ(EntriesInDir(), 0u);
}

TEST_F(AtomicFileTest, PointMapSaveFailureNamesThePathAndLeavesNoTemporary) {
  PointMap map;
  for (int i = 0; i < 20000; ++i) map.Insert({0.1 * i, 0.0}, 0.1);  // 480 kB of points
  const std::string path = dir_ + "/map.pcd";
  {
    const FileSizeLimit limit(64 * 1024);
    ExpectRuntimeErrorWith([&] { SavePointMapPcd(map, path); }, {path, "File too large"});
  }
  EXPECT_EQ(EntriesInDir(), 0u) << "neither map.pcd nor its temporary";
}

}  // namespace
}  // namespace scanloc
