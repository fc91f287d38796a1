#include "scanloc/report/iteration_selection.hpp"

#include <algorithm>
#include <cerrno>
#include <cstdlib>
#include <set>
#include <sstream>
#include <stdexcept>

namespace scanloc {
namespace {

// A range written "10-20" may not name more iterations than this (a typo would otherwise
// allocate a huge list).
constexpr std::size_t kMaxRangeLength = 1000000;

bool Localised(const IterationRow& row) {
  return !row.candidates.empty();
}

std::size_t ParseIndex(const std::string& text, const std::string& part) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos)
    throw std::invalid_argument("--iterations: expected an iteration number, got '" + part + "'");
  errno = 0;
  const unsigned long long value = std::strtoull(text.c_str(), nullptr, 10);
  if (errno == ERANGE) throw std::invalid_argument("--iterations: '" + part + "' is out of range");
  return static_cast<std::size_t>(value);
}

}  // namespace

std::vector<std::size_t> ParseIterationList(const std::string& text) {
  std::vector<std::size_t> indices;
  std::stringstream stream(text);
  for (std::string part; std::getline(stream, part, ',');) {
    part.erase(0, part.find_first_not_of(" \t"));
    part.erase(part.find_last_not_of(" \t") + 1);
    const std::size_t dash = part.find('-');
    if (dash == std::string::npos) {
      indices.push_back(ParseIndex(part, part));
      continue;
    }
    const std::size_t from = ParseIndex(part.substr(0, dash), part);
    const std::size_t to = ParseIndex(part.substr(dash + 1), part);
    if (to < from || to - from >= kMaxRangeLength)
      throw std::invalid_argument("--iterations: expected a range 'from-to' with from ≤ to, got '" +
                                  part + "'");
    for (std::size_t i = from; i <= to; ++i) indices.push_back(i);
  }
  if (indices.empty())
    throw std::invalid_argument("--iterations: expected iteration numbers like 3,10-12");
  return indices;
}

IterationSelection SelectIterations(const std::vector<IterationRow>& rows,
                                    const IterationSelectionOptions& options) {
  for (const std::size_t i : options.indices)
    if (i >= rows.size())
      throw std::invalid_argument("--iterations: iteration " + std::to_string(i) +
                                  " is not in the run (it has " + std::to_string(rows.size()) +
                                  ", numbered from 0)");
  std::vector<std::size_t> localised, flagged;
  for (const IterationRow& row : rows) {
    if (Localised(row)) localised.push_back(row.index);
    if (row.flagged()) flagged.push_back(row.index);
  }
  std::set<std::size_t> chosen(options.indices.begin(), options.indices.end());
  std::ostringstream rule;

  const std::size_t first = std::min(options.first, localised.size());
  chosen.insert(localised.begin(), localised.begin() + first);
  rule << "the first " << first << " localised";

  std::size_t every = options.every;
  if (every == 0 && options.spread > 0)
    every = std::max<std::size_t>(1, (localised.size() + options.spread - 1) / options.spread);
  if (every > 0) {
    std::size_t count = 0;
    for (std::size_t k = 0; k < localised.size(); k += every, ++count) chosen.insert(localised[k]);
    rule << "; one in every " << every << " localised (" << count << ")";
  }

  const std::size_t wanted = std::min(options.flagged, flagged.size());
  for (std::size_t k = 0; k < wanted; ++k) {
    // Evenly spread over the flagged ones, the first and the last included.
    const std::size_t at = wanted == 1 ? 0 : k * (flagged.size() - 1) / (wanted - 1);
    chosen.insert(flagged[at]);
  }
  rule << "; " << wanted << " of the " << flagged.size() << " flagged, evenly spread";
  if (!options.indices.empty()) rule << "; " << options.indices.size() << " named";

  IterationSelection selection;
  selection.indices.assign(chosen.begin(), chosen.end());
  rule << " — " << selection.indices.size() << " of " << rows.size() << " iterations drawn";
  selection.rule = rule.str();
  return selection;
}

}  // namespace scanloc
