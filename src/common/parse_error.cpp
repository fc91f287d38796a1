#include "scanloc/common/parse_error.hpp"

#include <cerrno>
#include <cmath>
#include <cstdlib>
#include <sstream>

namespace scanloc {

std::vector<std::string> SplitFields(const std::string& line) {
  const std::string content = line.substr(0, line.find('#'));
  std::istringstream stream(content);
  std::vector<std::string> fields;
  for (std::string field; stream >> field;) fields.push_back(field);
  return fields;
}

double ParseDouble(const std::string& field, const std::string& file, std::size_t line,
                   const std::string& what) {
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
