#pragma once
// Compact JSON text, byte for byte what nlohmann's dump() writes (no indentation, UTF-8 kept,
// numbers as nlohmann formats them), in a fraction of its time: a session writes one record per
// scan, and dump() was a twentieth of its instructions.

#include <nlohmann/json.hpp>
#include <string>

namespace scanloc {

// Appends value.dump() to `text`. Throws as dump() does (a string that is not valid UTF-8).
void AppendJsonText(const nlohmann::json& value, std::string& text);

}  // namespace scanloc
