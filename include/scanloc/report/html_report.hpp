#pragma once
// `scanloc report`: a run folder as one self-contained HTML page (inline SVG figures and CSS, no
// script, nothing fetched) that opens in a browser: the session summary, the trajectory over the
// final map, the moments over the session, the selected iterations on the map with their
// candidates, histograms and refinement, and a table of every iteration.

#include <string>
#include <vector>

#include "scanloc/report/iteration_selection.hpp"
#include "scanloc/report/run_contents.hpp"

namespace scanloc {

struct ReportOptions {
  IterationSelectionOptions selection;
  RunInputOverrides inputs;  // --log, --line-map instead of what summary.json names
  std::string output_path;   // "" → <run folder>/report.html
};

struct ReportResult {
  std::string path;       // where the page was written
  std::size_t bytes = 0;  // its size
  std::size_t iterations = 0;
  std::size_t drawn = 0;            // iterations drawn in detail
  std::size_t drawn_with_scan = 0;  // of those, with their scan
  std::string selection_rule;       // which were drawn, in words
  std::vector<std::string> notes;   // what was missing or unreadable (also on the page)
};

// The page for a run already read; fills `result` (but its path and bytes).
std::string RenderRunReport(const RunContents& run, const ReportOptions& options,
                            ReportResult& result);

// Reads the run folder, renders the page and writes it atomically. Throws what ReadRunContents
// throws, std::invalid_argument for a selection naming iterations the run does not have, and
// std::runtime_error when the page cannot be written.
ReportResult WriteRunReport(const std::string& run_directory, const ReportOptions& options = {});

}  // namespace scanloc
