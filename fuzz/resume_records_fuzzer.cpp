// ReadRecordsToResume (the complete lines of a run folder's iterations.jsonl, read back by
// `scanloc session --resume`) on arbitrary bytes; the records it returns must be numbered from 0,
// with finite postures and a histogram of counts that are not negative.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "scanloc/io/run_resume.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const scanloc::fuzz::InputFile input(".jsonl");
  const std::string& path = input.Write(data, size);
  scanloc::fuzz::AcceptDocumentedErrors([&] {
    const scanloc::RecordedRun run = scanloc::ReadRecordsToResume(path);
    scanloc::fuzz::Require(run.complete_bytes <= size, "complete_bytes beyond the file");
    for (std::size_t i = 0; i < run.iterations.size(); ++i) {
      const scanloc::RecordedIteration& r = run.iterations[i];
      scanloc::fuzz::Require(r.index == i, "records out of order were accepted");
      scanloc::fuzz::Require(scanloc::fuzz::FinitePose(r.T_world_robot),
                             "a record with a non-finite posture was accepted");
      if (r.kept_test)
        for (const int count : r.kept_test->histogram)
          scanloc::fuzz::Require(count >= 0, "a negative histogram count was accepted");
    }
  });
  return 0;
}
