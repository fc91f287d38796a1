#pragma once
// Candidate postures of the robot, one per line: `x y theta [label]` (metres, radians), with '#'
// comments and blank lines allowed; the label defaults to p0, p1, ... as in the chapter's tables.

#include <string>
#include <vector>

#include "scanloc/session/candidate.hpp"

namespace scanloc {

// Throws ParseError (file, line, what was expected) on malformed content.
std::vector<Candidate> ReadCandidatesFile(const std::string& path);
void WriteCandidatesFile(const std::vector<Candidate>& candidates, const std::string& path);

}  // namespace scanloc
