// CarmenReader on arbitrary bytes, message by message, resuming after each ParseError as the
// reader documents (so each error must name a later line than the one before); every laser record
// must carry a consistent scan. gzopen reads gzip data
// transparently, so corpus entries starting with the gzip magic fuzz the decompression too.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "scanloc/io/carmen_log.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const scanloc::fuzz::InputFile input(".clf");
  const std::string& path = input.Write(data, size);
  scanloc::fuzz::AcceptDocumentedErrors([&] {
    scanloc::CarmenReader reader(path);
    scanloc::CarmenRecord record;
    std::size_t last_error_line = 0;
    while (true) {
      try {
        if (!reader.Next(record)) break;
      } catch (const scanloc::ParseError& error) {
        // A malformed message; the next call starts at the following line.
        scanloc::fuzz::Require(
            error.line() > last_error_line,
            std::string("CarmenReader did not advance after a ParseError: ") + error.what());
        last_error_line = error.line();
        continue;
      }
      if (record.kind == scanloc::CarmenRecord::Kind::kLaser)
        scanloc::fuzz::RequireConsistentScan(record.scan);
      const double progress = reader.Progress();
      scanloc::fuzz::Require(progress >= 0.0 && progress <= 1.0, "Progress() outside [0, 1]");
    }
    reader.mounting();
  });
  return 0;
}
