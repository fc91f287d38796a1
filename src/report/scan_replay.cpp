#include "scanloc/report/scan_replay.hpp"

#include <algorithm>
#include <set>

#include "scanloc/io/sequence_sources.hpp"

namespace scanloc {
namespace {

// "dir/aces.clf.gz:273" → "aces.clf.gz:273": the session and the report may spell the log's
// folder differently.
std::string BaseOrigin(const std::string& origin) {
  const std::size_t slash = origin.find_last_of('/');
  return slash == std::string::npos ? origin : origin.substr(slash + 1);
}

}  // namespace

ScanReplayResult ReplayScans(const std::string& log_path, const std::vector<IterationRow>& rows,
                             const std::vector<std::size_t>& selected,
                             const LaserMounting& mounting, const MapExtensionOptions& extension,
                             PointMap& map, const ScanVisitor& visit) {
  ScanReplayResult result;
  const std::set<std::size_t> wanted(selected.begin(), selected.end());
  if (wanted.empty() || rows.empty()) return result;
  const std::size_t last = std::min(*wanted.rbegin(), rows.size() - 1);
  std::unique_ptr<IterationSource> source;
  try {
    source = OpenIterationSource(log_path);
  } catch (const std::exception& e) {
    result.problem = std::string("the sequence cannot be read: ") + e.what();
    return result;
  }
  Iteration iteration;
  for (std::size_t i = 0; i <= last; ++i) {
    bool more = false;
    try {
      more = source->Next(iteration);
    } catch (const std::exception& e) {
      result.problem = std::string("reading the sequence failed: ") + e.what();
      return result;
    }
    if (!more) {
      result.problem = "the sequence " + log_path + " ends after " + std::to_string(i) +
                       " scans, the run has " + std::to_string(rows.size()) +
                       " iterations: is it the same sequence?";
      return result;
    }
    ++result.scans_read;
    const IterationRow& row = rows[i];
    if (!row.origin.empty() && !iteration.origin.empty() &&
        BaseOrigin(row.origin) != BaseOrigin(iteration.origin)) {
      result.problem = "scan " + std::to_string(i) + " of " + log_path + " comes from " +
                       BaseOrigin(iteration.origin) + ", the run's from " + BaseOrigin(row.origin) +
                       ": is it the same sequence?";
      return result;
    }
    if (wanted.count(i)) {
      visit(row, iteration.scan, map);
      ++result.scans_visited;
    }
    if (row.inserted)
      ExtendMap(map, iteration.scan, mounting.LaserPose(row.T_world_robot), extension);
  }
  return result;
}

}  // namespace scanloc
