#pragma once
// A planar laser simulator over a line world: the "real" scans of our synthetic trials. The world
// may hold more than the map (clutter, machinery, people), which is what makes the test hard.

#include <cstdint>
#include <random>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/geometry/pose2d.hpp"
#include "scanloc/maps/line_map.hpp"

namespace scanloc {

struct LaserSimulatorOptions {
  std::size_t beam_count = 2400;     // points per revolution (the Acuity's 2,400)
  double fov_rad = 2.0 * M_PI;       // field of view, centred on the heading
  double range_max_m = 20.0;         // no echo at or beyond this
  double reliable_range_m = 10.0;    // beyond it returns go missing more and more often
  double range_noise_m = 0.02;       // Gaussian range noise σ at short range
  double range_noise_per_m = 0.001;  // σ grows by this per metre of range
  double dropout_probability = 0.0;  // missing returns anywhere
  // A sector of the sweep that hits the robot's own body, in the laser frame (empty when from ≥
  // to): those beams return body_range_m.
  double body_from_rad = 0.0;
  double body_to_rad = 0.0;
  double body_range_m = 0.35;
  // Throws std::invalid_argument naming the first option out of its domain.
  void Validate() const;
};

// Casts every beam against the world's segments (nearest hit), then adds noise and missing
// returns drawn from `rng`. Missing returns are coded -1.0 as in the trials.
LaserScan SimulateLaser(const LineMap& world, const Pose2D& T_world_laser,
                        const LaserSimulatorOptions& options, std::mt19937& rng);

}  // namespace scanloc
