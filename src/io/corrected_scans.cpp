#include "scanloc/io/corrected_scans.hpp"

#include <cmath>
#include <map>

#include "scanloc/io/trajectory.hpp"

namespace scanloc {

std::vector<CorrectedScan> ReadCorrectedScans(const std::string& log,
                                              const std::string& corrected_poses,
                                              CarmenOptions options) {
  std::map<long long, Pose2D> corrected;  // keyed by timestamp in 10 µs ticks
  for (const auto& p : ReadCorrectedPoses(corrected_poses))
    corrected[std::llround(p.timestamp_s * 1e5)] = p.pose;
  CarmenReader reader(log, std::move(options));
  std::vector<CorrectedScan> scans;
  CarmenRecord record;
  while (reader.Next(record)) {
    if (record.kind != CarmenRecord::Kind::kLaser) continue;
    const long long tick = std::llround(record.timestamp_s * 1e5);
    for (const long long t : {tick, tick - 1, tick + 1})
      if (const auto it = corrected.find(t); it != corrected.end()) {
        scans.push_back({std::move(record.scan), reader.mounting().LaserPose(it->second)});
        break;
      }
  }
  return scans;
}

}  // namespace scanloc
