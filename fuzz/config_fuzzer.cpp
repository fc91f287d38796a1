// LoadConfig (a JSON config file) on arbitrary bytes; a config it accepts must survive
// ToJson → ApplyJson unchanged, as `scanloc test --json` prints it for reuse.
#include <cstddef>
#include <cstdint>
#include <nlohmann/json.hpp>

#include "fuzz_support.hpp"
#include "scanloc/config/config.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  static const scanloc::fuzz::InputFile input(".json");
  const std::string& path = input.Write(data, size);
  scanloc::fuzz::AcceptDocumentedErrors([&] {
    const scanloc::Config config = scanloc::LoadConfig(path);
    const nlohmann::json printed = scanloc::ToJson(config);
    scanloc::Config reloaded;
    scanloc::ApplyJson(printed, reloaded);
    scanloc::fuzz::Require(scanloc::ToJson(reloaded) == printed,
                           "a loaded config does not survive ToJson then ApplyJson");
  });
  return 0;
}
