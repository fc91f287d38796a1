#include "scanloc/common/parse_error.hpp"

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdlib>

namespace scanloc {

namespace {

bool IsFieldSpace(char c) {
  return c == ' ' || c == '\t' || c == '\n' || c == '\v' || c == '\f' || c == '\r';
}

}  // namespace

void SplitFields(const std::string& line, std::size_t max_fields,
                 std::vector<std::string>& fields) {
  const std::size_t end = std::min(line.find('#'), line.size());
  std::size_t count = 0;
  std::size_t begin = 0;
  while (count <= max_fields) {
    while (begin < end && IsFieldSpace(line[begin])) ++begin;
    if (begin == end) break;
    std::size_t stop = begin;
    while (stop < end && !IsFieldSpace(line[stop])) ++stop;
    // Assigned into the strings already there: their buffers are reused line after line.
    if (count < fields.size())
      fields[count].assign(line, begin, stop - begin);
    else
      fields.emplace_back(line, begin, stop - begin);
    ++count;
    begin = stop;
  }
  fields.resize(count);
}

std::vector<std::string> SplitFields(const std::string& line, std::size_t max_fields) {
  std::vector<std::string> fields;
  SplitFields(line, max_fields, fields);
  return fields;
}

double ParseDouble(const std::string& field, const std::string& file, std::size_t line,
                   const std::string& what) {
  // std::from_chars first: correctly rounded like strtod, and several times faster (a log's
  // ranges are most of its parsing). Whatever it does not take whole (a sign '+', hexadecimal,
  // an out-of-range value) goes to strtod, whose verdict stands.
  double fast = 0.0;
  const auto [stop, error] = std::from_chars(field.data(), field.data() + field.size(), fast);
  if (error == std::errc() && stop == field.data() + field.size()) return fast;
  const char* begin = field.c_str();
  char* end = nullptr;
  errno = 0;
  const double value = std::strtod(begin, &end);
  if (end == begin || *end != '\0' || (errno == ERANGE && std::isinf(value)))
    throw ParseError(file, line, "expected " + what + ", got '" + field + "'");
  return value;
}

double ParseFiniteDouble(const std::string& field, const std::string& file, std::size_t line,
                         const std::string& what) {
  const double value = ParseDouble(field, file, line, what);
  if (!std::isfinite(value))
    throw ParseError(file, line, "expected a finite " + what + ", got '" + field + "'");
  return value;
}

long ParseInteger(const std::string& field, const std::string& file, std::size_t line,
                  const std::string& what) {
  const char* begin = field.c_str();
  char* end = nullptr;
  errno = 0;
  const long value = std::strtol(begin, &end, 10);
  if (end == begin || *end != '\0' || errno == ERANGE)
    throw ParseError(file, line, "expected " + what + ", got '" + field + "'");
  return value;
}

}  // namespace scanloc
