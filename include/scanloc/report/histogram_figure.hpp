#pragma once
// The distance histogram of the Likelihood Test before and after refinement, drawn like the
// chapter's Figures 7, 12 and 15: the slots on the horizontal axis, before in dark columns in the
// background, after in light columns in the foreground.

#include <string>

#include "scanloc/likelihood/likelihood_test.hpp"

namespace scanloc {

// `after` may be nullptr (no refinement): the histogram before alone. slot_width_m is Δslot;
// the last slot gathers all distances from (NS−1)·Δslot up to T_Map. `id` must be unique in the
// page.
std::string HistogramFigure(const LikelihoodTestResult& before, const LikelihoodTestResult* after,
                            double slot_width_m, const std::string& id);

// A small histogram for a table cell (no axes); the counts in its tooltip.
std::string HistogramSparkline(const std::vector<int>& histogram, const std::string& id);

}  // namespace scanloc
