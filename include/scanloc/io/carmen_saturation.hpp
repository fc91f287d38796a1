#pragma once
// Recognising a laser's "no return" code from its readings: a saturated laser (nothing within
// reach) reports one fixed value, its maximum (81.83 m in Intel, 50.00 in ACES, 32.767 in the
// Örebro log), and repeats it over many bearings and scans. Taken for a range, that value draws
// phantom walls; recognised, the readings at or above it carry no echo.

#include <cstddef>
#include <optional>
#include <vector>

namespace scanloc {

// One laser reading with the index of its beam in the scan.
struct BeamReading {
  double range_m = 0.0;
  std::size_t beam = 0;
};

// How a saturation code is told from a far wall. A code is the log's largest reading M, read
// together with the readings just below it (the band [M − band_fraction·M, M]: a log's code may
// jitter by a few mm, Örebro's between 32.759 and 32.767), when the band
// - holds at least min_readings readings (a far wall seen once or twice is not a code),
// - on at least min_beams different beams (a far wall seen while standing still repeats at the
//   same one or two beams; a saturated laser saturates wherever the space is open), and
// - holds more readings than the metre just below it (a code is a spike at the top of the
//   distribution; a far surface has a continuum of ranges below its farthest reading).
struct SaturationCriteria {
  double band_fraction = 1e-3;    // width of the band below the maximum, as a fraction of it
  std::size_t min_readings = 20;  // readings in the band
  std::size_t min_beams = 10;     // distinct beam indices in the band
  double below_band_m = 1.0;      // the span below the band it must outnumber, m
};

// The lowest reading of the saturation band when the readings show a saturation code (readings at
// or above it are no-return), nullopt otherwise. Non-finite and non-positive readings are ignored.
std::optional<double> RecogniseSaturation(const std::vector<BeamReading>& readings,
                                          const SaturationCriteria& criteria = {});

}  // namespace scanloc
