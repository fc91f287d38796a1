#pragma once
// Text input read line by line with a bound on a line's length, so that memory follows what a line
// can sensibly hold rather than the size of a file without newlines.

#include <cstddef>
#include <iosfwd>
#include <string>

namespace scanloc {

// The longest line a text reader accepts: 16 MiB. The longest sensible line is one scan at the
// beam cap (kMaxBeamsPerScan, 100,000) with a remission per beam: a CARMEN ROBOTLASER1 or a JSON
// Lines iteration of 200,000 numbers of up to about 20 characters, 4 MB. 16 MiB leaves four times
// that, while a 1 GB file without a newline costs 16 MiB before it is refused.
constexpr std::size_t kMaxLineBytes = std::size_t{16} << 20;

// Reads the next line of `in` (without its '\n') into `line`; false at the end of the input. Throws
// ParseError(path, line_number, ...) when the line is longer than `max_bytes`, after reading no
// more than max_bytes + 1 of it.
bool ReadBoundedLine(std::istream& in, std::string& line, const std::string& path,
                     std::size_t line_number, std::size_t max_bytes = kMaxLineBytes);

// The error for a line longer than `max_bytes`: file, line and the bound.
[[noreturn]] void ThrowLineTooLong(const std::string& path, std::size_t line_number,
                                   std::size_t max_bytes);

}  // namespace scanloc
