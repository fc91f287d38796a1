#include "scanloc/common/bounded_line.hpp"

#include <istream>

#include "scanloc/common/parse_error.hpp"

namespace scanloc {

void ThrowLineTooLong(const std::string& path, std::size_t line_number, std::size_t max_bytes) {
  throw ParseError(path, line_number,
                   "line longer than " + std::to_string(max_bytes) +
                       " bytes: expected a text file of lines (is it binary, or missing its "
                       "newlines?)");
}

bool ReadBoundedLine(std::istream& in, std::string& line, const std::string& path,
                     std::size_t line_number, std::size_t max_bytes) {
  line.clear();
  std::streambuf* buffer = in.rdbuf();
  if (!in.good() || buffer == nullptr) {
    in.setstate(std::ios::failbit);
    return false;
  }
  using Traits = std::char_traits<char>;
  bool any = false;
  for (Traits::int_type c = buffer->sbumpc(); !Traits::eq_int_type(c, Traits::eof());
       c = buffer->sbumpc()) {
    any = true;
    if (c == '\n') return true;
    if (line.size() == max_bytes) ThrowLineTooLong(path, line_number, max_bytes);
    line.push_back(Traits::to_char_type(c));
  }
  // The end of the input: a last line without a newline, or nothing at all.
  in.setstate(any ? std::ios::eofbit : std::ios::eofbit | std::ios::failbit);
  return any;
}

}  // namespace scanloc
