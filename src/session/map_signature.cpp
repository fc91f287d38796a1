#include "scanloc/session/map_signature.hpp"

#include <algorithm>
#include <chrono>

#include "scanloc/simulation/simulated_scan.hpp"

namespace scanloc {

LaidScanSample::LaidScanSample(std::size_t capacity)
    : capacity_(std::max<std::size_t>(capacity, 2)) {}

void LaidScanSample::Add(std::size_t index, const LaserScan& scan, const Pose2D& T_world_robot) {
  if (seen_++ % stride_ != 0) return;
  entries_.push_back({index, scan, T_world_robot});
  if (entries_.size() < capacity_) return;
  std::size_t kept = 0;
  for (std::size_t i = 0; i < entries_.size(); i += 2, ++kept)
    if (kept != i) entries_[kept] = std::move(entries_[i]);
  entries_.resize(kept);
  stride_ *= 2;
}

MapSignature MeasureMapSignature(const MapView& map, const LaidScanSample& sample,
                                 const std::vector<std::optional<Pose2D>>& corrected,
                                 const LaserMounting& mounting, const LocalisationOptions& options,
                                 const LaserSignatureOptions& signature_options) {
  const auto start = std::chrono::steady_clock::now();
  LaserSignatureOptions learning = signature_options;
  // The whole sample is remembered; a signature that learns nothing (window 0) stays so.
  if (learning.window > 0)
    learning.window = std::max(learning.min_samples, static_cast<int>(sample.entries().size()));
  LaserSignature signature(learning);
  MapSignature out;
  std::vector<double> expect_values_m;
  for (const LaidScanSample::Entry& e : sample.entries()) {
    const Pose2D posture =
        e.index < corrected.size() && corrected[e.index] ? *corrected[e.index] : e.T_world_robot;
    const LocalisationResult result =
        Localise(map, e.scan, {{posture, "laid"}}, mounting, options, RefinePolicy::kAll);
    if (result.refined.empty() || result.refined.front().test.valid_pairs == 0) continue;
    const RankedCandidate& refined = result.refined.front();
    signature.Add(refined.test);
    expect_values_m.push_back(refined.test.expect_value_m);
    out.samples.push_back(
        {refined.T_world_robot.x_m, refined.T_world_robot.y_m, refined.test.expect_value_m});
  }
  out.scans = expect_values_m.size();
  out.learned = signature.learned();
  out.max_expect_value_m = signature.ExpectValueBound(options.validation.max_expect_value_m);
  if (!expect_values_m.empty()) {
    auto middle = expect_values_m.begin() + expect_values_m.size() / 2;
    std::nth_element(expect_values_m.begin(), middle, expect_values_m.end());
    out.median_expect_value_m = *middle;
  }
  out.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return out;
}

}  // namespace scanloc
