#pragma once
// The wide search: candidate postures for a scan over a window of translations and headings,
// found by correlative scan matching (Olson 2009) with exact branch and bound over translations
// (Hess et al. 2016). Each posture is scored by the mean likelihood-field value at the scan's
// endpoints; the best few distinct ones go to Localise, where the Likelihood Test decides. It is
// how a lost session searches around its odometry, how a loop is closed against old nodes, and,
// with the whole map as its window, how a robot finds itself on a saved map.

#include <optional>
#include <vector>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/geometry/pose2d.hpp"
#include "scanloc/maps/likelihood_field.hpp"
#include "scanloc/simulation/simulated_scan.hpp"

namespace scanloc {

// The postures searched: the laser within ±half_width_m of centre's position in x and y, and
// within ±half_yaw_rad of its heading (±π: every heading).
struct SearchWindow {
  Pose2D centre;  // T_world_laser
  double half_width_m = 1.0;
  double half_yaw_rad = 0.35;
};

struct WideSearchOptions {
  LikelihoodFieldOptions field;  // the grid scored against: resolution, σ, levels
  int max_candidates = 5;        // distinct postures returned, best first
  // Postures closer than both of these to a better one are not distinct.
  double min_separation_m = 0.3;
  double min_separation_rad = 0.1;
  int max_beams = 120;  // valid beams scored, evenly subsampled: bounds the cost per scan
  // Headings are searched a step apart that moves the farthest endpoint by one cell (Hess et al.
  // 2016), but not finer than this: the refinement that follows converges from within a degree.
  double min_heading_step_rad = 0.0087;
  // Blocks whose every posture lies near a kept better one are not searched: they could not
  // change the result (the same candidates either way; off only to show that in a test).
  bool skip_shadowed_blocks = true;
  // Throws std::invalid_argument naming the first option out of its domain.
  void Validate() const;
};

struct SearchCandidate {
  Pose2D T_world_laser;
  double score = 0.0;  // mean field value over the scored beams, in [0, 1]
};

struct WideSearchResult {
  std::vector<SearchCandidate> candidates;  // distinct, best first
  int headings = 0;                         // headings searched
  long long nodes_scored = 0;               // branch-and-bound nodes scored, leaves included
  double time_s = 0.0;
};

// Searches `window` for postures of `scan` against `map` (the line map sampled at half the
// field's resolution, and the point map's points). An empty map or a scan without a valid range
// gives no candidate. With `storage`, the field is built there (its former contents replaced):
// a caller searching again and again keeps one and saves allocating megabytes afresh.
WideSearchResult WideSearch(const MapView& map, const LaserScan& scan, const SearchWindow& window,
                            const WideSearchOptions& options = {},
                            LikelihoodField* storage = nullptr);

// The window over a whole map, every heading: the laser anywhere in the square about the box of
// its points and segments (a global search). Nullopt for an empty map.
std::optional<SearchWindow> WholeMapWindow(const MapView& map);

}  // namespace scanloc
