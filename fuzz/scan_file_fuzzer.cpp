// ReadScanFile (the native *.scan format) on arbitrary bytes; a scan it returns must be
// consistent.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "scanloc/io/scan_file.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const scanloc::fuzz::InputFile input(".scan");
  const std::string& path = input.Write(data, size);
  scanloc::fuzz::AcceptDocumentedErrors(
      [&] { scanloc::fuzz::RequireConsistentScan(scanloc::ReadScanFile(path)); });
  return 0;
}
