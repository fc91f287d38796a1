#pragma once
// Earlier results are not replaced by accident: a command that writes a folder of results (a run
// folder, a simulated environment) or named result files refuses to write over existing ones
// unless told to (`--force`).

#include <string>
#include <vector>

namespace scanloc {

// Throws std::runtime_error when `dir` exists and is not a folder, or, unless `force`, when it is
// a folder with anything in it; the message names the folder, one of its entries and --force.
// Nothing is created or changed.
void RefuseNonEmptyFolder(const std::string& dir, bool force);

// Throws std::runtime_error naming the first of `paths` that exists, unless `force`.
void RefuseToReplace(const std::vector<std::string>& paths, bool force);

}  // namespace scanloc
