#include "scanloc/io/carmen_saturation.hpp"

#include <algorithm>
#include <cmath>
#include <set>

namespace scanloc {

std::optional<double> RecogniseSaturation(const std::vector<BeamReading>& readings,
                                          const SaturationCriteria& criteria) {
  auto usable = [](double r) { return std::isfinite(r) && r > 0.0; };
  double max_m = 0.0;
  for (const BeamReading& reading : readings)
    if (usable(reading.range_m)) max_m = std::max(max_m, reading.range_m);
  if (max_m <= 0.0) return std::nullopt;

  const double band_start_m = max_m * (1.0 - criteria.band_fraction);
  const double below_start_m = band_start_m - criteria.below_band_m;
  std::size_t in_band = 0, below_band = 0;
  double lowest_in_band_m = max_m;
  std::set<std::size_t> beams;
  for (const BeamReading& reading : readings) {
    if (!usable(reading.range_m)) continue;
    if (reading.range_m >= band_start_m) {
      ++in_band;
      lowest_in_band_m = std::min(lowest_in_band_m, reading.range_m);
      if (beams.size() < criteria.min_beams) beams.insert(reading.beam);
    } else if (reading.range_m >= below_start_m) {
      ++below_band;
    }
  }
  const bool saturated = in_band >= criteria.min_readings && beams.size() >= criteria.min_beams &&
                         in_band > below_band;
  if (!saturated) return std::nullopt;
  return lowest_in_band_m;
}

}  // namespace scanloc
