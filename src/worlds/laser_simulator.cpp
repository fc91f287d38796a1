#include "scanloc/worlds/laser_simulator.hpp"

#include <cmath>
#include <stdexcept>
#include <string>

#include "scanloc/simulation/simulated_scan.hpp"

namespace scanloc {

void LaserSimulatorOptions::Validate() const {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("LaserSimulatorOptions: ") + what);
  };
  require(beam_count >= 2 && beam_count <= 1000000, "beam_count must be in [2, 1000000]");
  require(fov_rad > 0.0 && fov_rad <= 2.0 * M_PI, "fov_rad must be in (0, 2π]");
  require(range_max_m > 0.0 && std::isfinite(range_max_m), "range_max_m must be positive");
  require(reliable_range_m > 0.0, "reliable_range_m must be positive");
  require(range_noise_m >= 0.0 && range_noise_per_m >= 0.0, "noise must be >= 0");
  require(dropout_probability >= 0.0 && dropout_probability <= 1.0,
          "dropout_probability must be in [0, 1]");
  require(body_range_m > 0.0, "body_range_m must be positive");
}

LaserScan SimulateLaser(const LineMap& world, const Pose2D& T_world_laser,
                        const LaserSimulatorOptions& options, std::mt19937& rng) {
  options.Validate();
  LaserScan scan;
  scan.layout = MakeLayout(options.beam_count, options.fov_rad, options.range_max_m);
  const SimulatedScan exact = SimulateFromLines(world, scan.layout, T_world_laser);
  std::normal_distribution<double> unit_noise(0.0, 1.0);
  std::uniform_real_distribution<double> uniform(0.0, 1.0);
  scan.ranges_m.assign(scan.layout.beam_count, -1.0);
  for (std::size_t k = 0; k < scan.layout.beam_count; ++k) {
    // Draw every random number for every beam so that one option does not shift the others' draws.
    const double noise = unit_noise(rng), dropout = uniform(rng), unreliable = uniform(rng);
    const double bearing = NormalizeAngle(scan.layout.Bearing(k));
    if (options.body_from_rad < options.body_to_rad && bearing >= options.body_from_rad &&
        bearing <= options.body_to_rad) {
      scan.ranges_m[k] = options.body_range_m;
      continue;
    }
    if (!exact.IsValid(k) || dropout < options.dropout_probability) continue;
    const double range = exact.ranges_m[k];
    // Past the reliable range the echo is lost with a probability growing linearly to 1 at the
    // maximum range.
    if (range > options.reliable_range_m && options.range_max_m > options.reliable_range_m &&
        unreliable <
            (range - options.reliable_range_m) / (options.range_max_m - options.reliable_range_m))
      continue;
    const double sigma = options.range_noise_m + options.range_noise_per_m * range;
    const double noisy = range + sigma * noise;
    if (noisy > 0.0 && noisy < options.range_max_m) scan.ranges_m[k] = noisy;
  }
  return scan;
}

}  // namespace scanloc
