// The CARMEN reader of carmen_log_fuzzer on the input gzip-compressed first (a .clf.gz), so that
// the text goes through zlib's line assembly.
#include <zlib.h>

#include <cstddef>
#include <cstdint>
#include <cstdlib>

#include "fuzz_support.hpp"
#include "scanloc/io/carmen_log.hpp"

namespace {

void WriteGzip(const std::uint8_t* data, std::size_t size, const std::string& path) {
  gzFile file = gzopen(path.c_str(), "wb1");
  if (file == nullptr || (size > 0 && gzwrite(file, data, static_cast<unsigned>(size)) == 0) ||
      gzclose(file) != Z_OK)
    std::abort();  // the harness, not the reader, failed
}

}  // namespace

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const scanloc::fuzz::InputFile input(".clf.gz");
  WriteGzip(data, size, input.path());
  scanloc::fuzz::AcceptDocumentedErrors([&] {
    scanloc::CarmenReader reader(input.path());
    scanloc::CarmenRecord record;
    std::size_t last_error_line = 0;
    while (true) {
      try {
        if (!reader.Next(record)) break;
      } catch (const scanloc::ParseError& error) {
        scanloc::fuzz::Require(
            error.line() > last_error_line,
            std::string("CarmenReader did not advance after a ParseError: ") + error.what());
        last_error_line = error.line();
        continue;
      }
      if (record.kind == scanloc::CarmenRecord::Kind::kLaser)
        scanloc::fuzz::RequireConsistentScan(record.scan);
    }
  });
  return 0;
}
