// SequenceFileSource (the native *.seq.jsonl format) on arbitrary bytes, iteration by iteration
// until the end or the first error; every iteration must carry a consistent scan.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "scanloc/io/sequence_sources.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const scanloc::fuzz::InputFile input(".seq.jsonl");
  const std::string& path = input.Write(data, size);
  scanloc::fuzz::AcceptDocumentedErrors([&] {
    scanloc::SequenceFileSource source(path);
    scanloc::Iteration iteration;
    while (source.Next(iteration)) {
      scanloc::fuzz::RequireConsistentScan(iteration.scan);
      source.truth();
      source.Progress();
    }
  });
  return 0;
}
