#include "scanloc/report/run_comparison.hpp"

#include <algorithm>
#include <cmath>
#include <iomanip>
#include <map>
#include <ostream>
#include <stdexcept>

#include "scanloc/report/run_contents.hpp"
#include "scanloc/report/series_figure.hpp"

namespace scanloc {
namespace {

std::string MapOf(const nlohmann::json& summary) {
  const auto inputs = summary.find("inputs");
  if (inputs == summary.end() || !inputs->is_object()) return "unknown";
  const bool lines = inputs->contains("line_map") && !(*inputs)["line_map"].is_null();
  const bool points = inputs->contains("point_map") && !(*inputs)["point_map"].is_null();
  return lines && points ? "both" : lines ? "line map" : points ? "point map" : "grown";
}

RunSide Side(const RunContents& run) {
  RunSide side;
  side.directory = run.directory;
  side.map = MapOf(run.summary);
  if (const auto it = run.summary.find("first_confirmed_scan");
      it != run.summary.end() && it->is_number())
    side.first_confirmed = it->get<std::size_t>();
  double ev = 0.0, ratio = 0.0, ms = 0.0;
  for (const IterationRow& row : run.iterations.rows) {
    ++side.scans;
    side.localised += !row.skipped;
    side.posed += row.posed;
    ms += row.total_ms;
    if (!row.validated) continue;
    ++side.validated;
    if (const LikelihoodTestResult* test = FinalTest(row)) {
      ev += test->expect_value_m;
      ratio += test->MatchRatio();
    }
  }
  if (side.validated > 0) {
    side.mean_expect_value_m = ev / side.validated;
    side.mean_match_ratio = ratio / side.validated;
  }
  if (side.scans > 0) side.mean_iteration_ms = ms / side.scans;
  return side;
}

// Distances between the postures two runs gave the same scans (matched by timestamp).
void Against(const RunContents& first, const RunContents& run, RunSide& side) {
  std::map<double, Pose2D> reference;
  for (const IterationRow& row : first.iterations.rows)
    if (row.posed) reference.emplace(row.timestamp_s, row.T_world_robot);
  std::vector<double> distances;
  for (const IterationRow& row : run.iterations.rows) {
    const auto it = reference.find(row.timestamp_s);
    if (!row.posed || it == reference.end()) continue;
    distances.push_back(
        std::hypot(row.T_world_robot.x_m - it->second.x_m, row.T_world_robot.y_m - it->second.y_m));
  }
  side.compared = distances.size();
  if (distances.empty()) return;
  std::sort(distances.begin(), distances.end());
  side.median_distance_m = distances[distances.size() / 2];
  side.max_distance_m = distances.back();
}

}  // namespace

std::vector<RunSide> CompareRuns(const std::vector<std::string>& directories) {
  if (directories.empty()) throw std::invalid_argument("compare: no run folder given");
  std::vector<RunSide> sides;
  std::optional<RunContents> first;
  for (const std::string& directory : directories) {
    RunContents run = ReadRunContents(directory);
    if (run.iterations.rows.empty())
      throw std::runtime_error("compare: " + directory + " has no iteration (iterations.jsonl)");
    sides.push_back(Side(run));
    if (first) Against(*first, run, sides.back());
    if (!first) first = std::move(run);
  }
  return sides;
}

void PrintRunComparison(std::ostream& out, const std::vector<RunSide>& sides) {
  out << std::left << std::setw(28) << "run" << std::setw(11) << "map" << std::right << std::setw(7)
      << "scans" << std::setw(10) << "validated" << std::setw(11) << "confirmed" << std::setw(9)
      << "EV [cm]" << std::setw(12) << "match ratio" << std::setw(10) << "ms/scan" << std::setw(22)
      << "vs first: median/max"
      << "\n";
  out << std::fixed;
  for (const RunSide& s : sides) {
    const std::string name =
        s.directory.size() > 27 ? "…" + s.directory.substr(s.directory.size() - 26) : s.directory;
    out << std::left << std::setw(28) << name << std::setw(11) << s.map << std::right
        << std::setw(7) << s.scans << std::setw(10) << s.validated << std::setw(11)
        << (s.first_confirmed ? "scan " + std::to_string(*s.first_confirmed) : std::string("—"))
        << std::setw(9) << std::setprecision(2) << 100.0 * s.mean_expect_value_m << std::setw(12)
        << std::setprecision(3) << s.mean_match_ratio << std::setw(10) << std::setprecision(1)
        << s.mean_iteration_ms;
    if (s.median_distance_m)
      out << std::setw(13) << std::setprecision(3) << *s.median_distance_m << " / "
          << std::setprecision(3) << *s.max_distance_m << " m";
    out << "\n";
  }
}

}  // namespace scanloc
