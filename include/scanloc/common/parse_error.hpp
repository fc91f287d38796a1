#pragma once
// The error raised for bad data read from outside: it names the file, the line and what was
// expected.

#include <stdexcept>
#include <string>
#include <vector>

namespace scanloc {

class ParseError : public std::runtime_error {
 public:
  ParseError(const std::string& file, std::size_t line, const std::string& what)
      : std::runtime_error(file + ":" + std::to_string(line) + ": " + what),
        file_(file),
        line_(line) {}
  const std::string& file() const { return file_; }
  std::size_t line() const { return line_; }

 private:
  std::string file_;
  std::size_t line_;
};

// Splits a line into whitespace-separated fields, dropping a trailing `#` comment. Stops after
// max_fields + 1 fields: a caller that expects at most max_fields sees that there are too many
// without a long line costing a string per field.
std::vector<std::string> SplitFields(const std::string& line,
                                     std::size_t max_fields = static_cast<std::size_t>(-1) - 1);
// The same into `fields`, reusing its strings (a log's lines, one after another).
void SplitFields(const std::string& line, std::size_t max_fields, std::vector<std::string>& fields);

// Parses a finite double or throws ParseError naming `what` (e.g. "x1 in metres").
double ParseFiniteDouble(const std::string& field, const std::string& file, std::size_t line,
                         const std::string& what);
// Parses a double that may be non-finite ("nan", "inf"): scan ranges carry those.
double ParseDouble(const std::string& field, const std::string& file, std::size_t line,
                   const std::string& what);
long ParseInteger(const std::string& field, const std::string& file, std::size_t line,
                  const std::string& what);

}  // namespace scanloc
