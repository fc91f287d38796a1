#pragma once
// A run folder read back to resume its session (`scanloc session --resume`): the complete records
// of iterations.jsonl as what the session needs to replay them (session/replay.hpp). A run killed
// while writing leaves at most one incomplete last line; it is not a record, and the resumed run
// writes over it.

#include <cstdint>
#include <nlohmann/json_fwd.hpp>
#include <string>
#include <vector>

#include "scanloc/session/replay.hpp"

namespace scanloc {

struct RecordedRun {
  std::vector<RecordedIteration> iterations;  // one per complete line, in order
  std::uintmax_t complete_bytes = 0;          // the bytes of those lines, newlines included
  bool partial_line = false;                  // an incomplete line followed them
};

// What one record (a line of iterations.jsonl, parsed) says. Throws std::invalid_argument naming
// the key that is missing or of the wrong type.
RecordedIteration RecordedFromJson(const nlohmann::json& record);

// Reads the complete lines of iterations.jsonl at `path`. Throws ParseError (file, line, what was
// expected) for a complete line that is not a record, or for records out of order.
RecordedRun ReadRecordsToResume(const std::string& path);

}  // namespace scanloc
