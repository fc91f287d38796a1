#pragma once
// Which reader a recorded sequence needs, told by the file's content rather than its name.

#include <string>

namespace scanloc {

enum class InputFormat {
  kCarmenLog,     // CARMEN messages (FLASER, ROBOTLASER1, ODOM, PARAM, ...), plain or gzip
  kRosBag,        // a ROS 1 bag: starts with "#ROSBAG V2.0"
  kScanSequence,  // scanloc's JSON Lines sequence: starts with '{' ({"scanloc_sequence": 1, ...})
};

// What each format looks like, for error messages.
std::string AcceptedInputFormats();

// Looks at the first bytes (up to 64 KiB, decompressed when gzip): the ROS bag magic, a JSON
// object, or lines that start with a CARMEN message keyword. Throws std::runtime_error naming the
// file when it cannot be read or is none of these, listing the formats accepted.
InputFormat DetectInputFormat(const std::string& path);

}  // namespace scanloc
