// ReadIterationRows (a run folder's iterations.jsonl as `scanloc report` and `scanloc evaluate
// --closures` read it) on arbitrary bytes; the rows it returns must be numbered from 0, with
// finite postures, and a closure's old scan must be a number it read.
#include <cmath>
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "scanloc/report/run_records.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const scanloc::fuzz::InputFile input(".jsonl");
  const std::string& path = input.Write(data, size);
  scanloc::fuzz::AcceptDocumentedErrors([&] {
    const scanloc::IterationRows read = scanloc::ReadIterationRows(path);
    for (std::size_t i = 0; i < read.rows.size(); ++i) {
      const scanloc::IterationRow& row = read.rows[i];
      scanloc::fuzz::Require(row.index == i, "rows out of order were accepted");
      scanloc::fuzz::Require(
          scanloc::fuzz::FinitePose(row.T_world_robot) && scanloc::fuzz::FinitePose(row.prediction),
          "a row with a non-finite posture was accepted");
      if (row.closure && row.closure->T_old_robot)
        scanloc::fuzz::Require(scanloc::fuzz::FinitePose(*row.closure->T_old_robot),
                               "a closure with a non-finite measurement was accepted");
      for (const scanloc::CandidateRow& candidate : row.candidates)
        for (const int count : candidate.test.histogram)
          scanloc::fuzz::Require(count >= 0, "a negative histogram count was accepted");
    }
  });
  return 0;
}
