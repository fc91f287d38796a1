#pragma once
// Text placed in HTML or SVG: escaped, and numbers written for people to read.

#include <string>
#include <string_view>

namespace scanloc {

// Escapes & < > " ' for element content and attribute values alike; control characters other
// than tab and newline (not allowed in XML) become U+FFFD.
std::string EscapeMarkup(std::string_view text);

// `value` with `decimals` digits after the point; "–" when not finite.
std::string FormatFixed(double value, int decimals);

// A byte count as "812 B", "14.2 kB", "3.1 MB".
std::string FormatBytes(double bytes);

}  // namespace scanloc
