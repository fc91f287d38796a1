#include "scanloc/likelihood/posture_scoring.hpp"

#include <algorithm>
#include <cmath>
#include <optional>

namespace scanloc {

PostureScore ScorePosture(const MapView& map, const LaserScan& scan, const Pose2D& T_world_laser,
                          const ScoringOptions& options) {
  PostureScore score;
  score.simulated = Simulate(map, scan.layout, T_world_laser, options.simulation);
  score.test = RunLikelihoodTest(scan, score.simulated, options.test);
  score.distance = RunLikelihoodDistance(scan, score.simulated, options.distance);
  return score;
}

namespace {

// Beams [first, first + layout.beam_count) of a simulation over a wider sweep, as a simulation
// with `layout`.
SimulatedScan Slice(const SimulatedScan& wide, std::size_t first, const ScanLayout& layout) {
  SimulatedScan sim;
  sim.layout = layout;
  const auto from = static_cast<std::ptrdiff_t>(first);
  const auto to = from + static_cast<std::ptrdiff_t>(layout.beam_count);
  sim.ranges_m.assign(wide.ranges_m.begin() + from, wide.ranges_m.begin() + to);
  sim.hit_source.assign(wide.hit_source.begin() + from, wide.hit_source.begin() + to);
  sim.hit_index.assign(wide.hit_index.begin() + from, wide.hit_index.begin() + to);
  return sim;
}

// The whole number of beam steps from heading a to heading b, if it is one.
std::optional<long> BeamSteps(double a_rad, double b_rad, double increment_rad) {
  const double steps = NormalizeAngle(b_rad - a_rad) / increment_rad;
  const double rounded = std::round(steps);
  if (std::abs(steps - rounded) > 1e-6) return std::nullopt;
  return static_cast<long>(rounded);
}

}  // namespace

std::vector<PostureScore> ScorePostures(const MapView& map, const LaserScan& scan,
                                        const std::vector<Pose2D>& T_world_laser,
                                        const ScoringOptions& options) {
  std::vector<PostureScore> scores(T_world_laser.size());
  std::vector<bool> done(T_world_laser.size(), false);
  const ScanLayout& layout = scan.layout;
  const double increment = layout.angle_increment_rad;
  for (std::size_t i = 0; i < T_world_laser.size(); ++i) {
    if (done[i]) continue;
    // The postures at this one's position whose headings are whole beam steps away.
    std::vector<std::pair<std::size_t, long>> group;
    long min_steps = 0, max_steps = 0;
    for (std::size_t j = i; j < T_world_laser.size(); ++j) {
      if (done[j] ||
          (T_world_laser[j].Translation() - T_world_laser[i].Translation()).norm() > 1e-9)
        continue;
      const auto steps = BeamSteps(T_world_laser[i].yaw_rad, T_world_laser[j].yaw_rad, increment);
      if (!steps) continue;
      group.emplace_back(j, *steps);
      min_steps = std::min(min_steps, *steps);
      max_steps = std::max(max_steps, *steps);
    }
    ScanLayout wide = layout;
    wide.beam_count = layout.beam_count + static_cast<std::size_t>(max_steps - min_steps);
    wide.angle_min_rad = layout.angle_min_rad + min_steps * increment;
    // One sweep must not wrap onto itself; otherwise each posture is simulated on its own.
    if (group.size() < 2 || wide.beam_count * increment > 2.0 * M_PI + 1e-9) group.resize(1);
    const SimulatedScan simulated =
        group.size() < 2 ? Simulate(map, layout, T_world_laser[i], options.simulation)
                         : Simulate(map, wide, T_world_laser[i], options.simulation);
    for (const auto& [j, steps] : group) {
      PostureScore& score = scores[j];
      score.simulated = group.size() < 2
                            ? simulated
                            : Slice(simulated, static_cast<std::size_t>(steps - min_steps), layout);
      score.test = RunLikelihoodTest(scan, score.simulated, options.test);
      score.distance = RunLikelihoodDistance(scan, score.simulated, options.distance);
      done[j] = true;
    }
  }
  return scores;
}

}  // namespace scanloc
