#pragma once
// The report's tables: the session summary, each drawn iteration's candidates and refinement
// (the chapter's Tables 1 and 2: MP, NVP, EV, dispersion, cost, reason), and one row for every
// iteration of the run. Every text is escaped.

#include <nlohmann/json.hpp>
#include <set>
#include <string>
#include <vector>

#include "scanloc/report/run_records.hpp"

namespace scanloc {

// Counts from the iterations themselves, then what summary.json adds (times, memory, inputs).
std::string SummaryTable(const nlohmann::json& summary, const std::vector<IterationRow>& rows);

// One row per candidate with its histogram; a message when there are none or none is valid.
// `id` prefixes the sparklines' ids.
std::string CandidateTable(const IterationRow& row, const std::string& id);

// Before and after refinement of the chosen candidate, then every refined candidate's verdict;
// "" when nothing was refined.
std::string RefinementTable(const IterationRow& row);

// One row per iteration; those in `drawn` link to their sections.
std::string IterationsTable(const std::vector<IterationRow>& rows,
                            const std::set<std::size_t>& drawn);

}  // namespace scanloc
