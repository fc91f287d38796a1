#pragma once
// Which iterations the report draws in detail: a session has thousands, a person looks at tens.
// The rule is the union of the parts below and is printed on the page.

#include <string>
#include <vector>

#include "scanloc/report/run_records.hpp"

namespace scanloc {

struct IterationSelectionOptions {
  std::size_t first = 3;     // the first N iterations that were localised (had candidates)
  std::size_t every = 0;     // every K-th localised iteration; 0: K chosen to give about `spread`
  std::size_t spread = 12;   // how many `every` aims at when K is chosen (0: none)
  std::size_t flagged = 12;  // up to N flagged ones (localised, not validated), evenly spread
  std::vector<std::size_t> indices;  // iterations named by the operator (--iterations)
};

struct IterationSelection {
  std::vector<std::size_t> indices;  // ascending, no repeats
  std::string rule;                  // the rule in words, with the counts
};

// Throws std::invalid_argument when a named iteration is not in the run.
IterationSelection SelectIterations(const std::vector<IterationRow>& rows,
                                    const IterationSelectionOptions& options);

// "3,10-12,40" → {3, 10, 11, 12, 40}; throws std::invalid_argument naming the bad part.
std::vector<std::size_t> ParseIterationList(const std::string& text);

}  // namespace scanloc
