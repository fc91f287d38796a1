#pragma once
// Loop closures over the session (issue 16's "per closure, the correction it applied"): for every
// closure whose scan was matched against the old nodes, how far that match put the scan from the
// session's own posture, in translation and in heading; the accepted ones in the closure colour,
// the rest grey; and for the accepted ones, the largest node displacement of the pose graph's solve
// that followed (what the map received).

#include <optional>
#include <string>
#include <vector>

#include "scanloc/report/run_records.hpp"

namespace scanloc {

// One closure tried after a scan whose posture was matched against the old nodes.
struct ClosureSample {
  std::size_t index = 0;          // the scan's iteration
  std::size_t old_iteration = 0;  // the old scan it was matched with
  bool accepted = false;
  double shift_m = 0.0;      // the matched posture's distance from the session's
  double heading_rad = 0.0;  // and its heading, matched minus session's, in (−π, π]
  std::optional<double> applied_m;  // accepted: the solve's largest node displacement
};

// The closures of `rows` that carry a matched posture (the others were not refined), in order.
std::vector<ClosureSample> ClosureSamples(const std::vector<IterationRow>& rows);

// Two panels over the iterations, translation [cm] and heading [deg]; a message when no closure
// was matched. `id` must be unique in the page.
std::string ClosureCorrectionFigure(const std::vector<IterationRow>& rows, const std::string& id);

}  // namespace scanloc
