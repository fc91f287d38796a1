// ReadLineMap (*.lines) on arbitrary bytes; every segment it returns must have finite vertices.
#include <cstddef>
#include <cstdint>

#include "fuzz_support.hpp"
#include "scanloc/maps/line_map.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const scanloc::fuzz::InputFile input(".lines");
  const std::string& path = input.Write(data, size);
  scanloc::fuzz::AcceptDocumentedErrors([&] {
    for (const scanloc::Segment& segment : scanloc::ReadLineMap(path).segments)
      scanloc::fuzz::Require(segment.a.allFinite() && segment.b.allFinite(),
                             "ReadLineMap returned a non-finite vertex");
  });
  return 0;
}
