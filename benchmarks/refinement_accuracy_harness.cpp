// Refinement on real scans: for each public log, a reference point map is built from the scans
// with corrected poses (every other one), the held-out scans are perturbed (fixed seed) and refined
// by every method, and the results are scored against the corrected poses. All methods run in the
// same process, on the same scans, interleaved scan by scan, so their times compare side by side.
//
//   refinement_accuracy_harness [--datasets DIR] [--scans N] [--seed S] [--offset-m D]
//                               [--offset-rad A] [--methods LIST] [--logs intel,aces,fr079]

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <random>
#include <string>
#include <vector>

#include "scanloc/io/corrected_scans.hpp"
#include "scanloc/likelihood/candidate_ranking.hpp"
#include "scanloc/maps/point_map.hpp"
#include "scanloc/refinement/refiner.hpp"

namespace {

using namespace scanloc;

struct MethodSpec {
  std::string name;
  RefinerOptions options;
};

std::vector<MethodSpec> AllMethods() {
  std::vector<MethodSpec> methods;
  for (const auto association :
       {PointAssociation::kNearestEndpoint, PointAssociation::kSimulatedHit})
    for (const auto weighting :
         {IncidenceWeighting::kCosine, IncidenceWeighting::kNone, IncidenceWeighting::kGate}) {
      RefinerOptions o;
      o.method = RefinementMethod::kCeres;
      o.ceres.incidence = weighting;
      o.ceres.point_association = association;
      methods.push_back({std::string("ceres-") + ToString(weighting) + "-" +
                             (association == PointAssociation::kSimulatedHit ? "sim" : "nn"),
                         o});
    }
  RefinerOptions ed;
  ed.method = RefinementMethod::kErrorDescent;
  methods.push_back({"error-descent", ed});
  RefinerOptions icp;
  icp.method = RefinementMethod::kIcp;
  methods.push_back({"icp-point", icp});
  icp.icp.point_to_plane = true;
  methods.push_back({"icp-line", icp});
  return methods;
}

double Median(std::vector<double> values) {
  if (values.empty()) return NAN;
  std::nth_element(values.begin(), values.begin() + values.size() / 2, values.end());
  return values[values.size() / 2];
}

}  // namespace

int main(int argc, char** argv) {
  std::string datasets =
      std::getenv("SCANLOC_DATASETS") ? std::getenv("SCANLOC_DATASETS") : "../shared/datasets";
  int scans_per_dataset = 100;
  unsigned seed = 1;
  double offset_m = 0.2, offset_rad = 0.05;
  std::string only_methods, only_logs;
  for (int i = 1; i + 1 < argc; i += 2) {
    const std::string key = argv[i], value = argv[i + 1];
    if (key == "--datasets")
      datasets = value;
    else if (key == "--scans")
      scans_per_dataset = std::stoi(value);
    else if (key == "--seed")
      seed = static_cast<unsigned>(std::stoul(value));
    else if (key == "--offset-m")
      offset_m = std::stod(value);
    else if (key == "--offset-rad")
      offset_rad = std::stod(value);
    else if (key == "--methods")
      only_methods = "," + value + ",";
    else if (key == "--logs")
      only_logs = "," + value + ",";
    else {
      std::fprintf(stderr, "unknown option %s\n", key.c_str());
      return 2;
    }
  }
  if (!std::filesystem::is_directory(datasets)) {
    std::fprintf(stderr, "datasets folder %s not found (set SCANLOC_DATASETS)\n", datasets.c_str());
    return 2;
  }
  std::vector<MethodSpec> methods;
  for (auto& m : AllMethods())
    if (only_methods.empty() || only_methods.find("," + m.name + ",") != std::string::npos)
      methods.push_back(m);

  std::printf(
      "Refinement from perturbed postures (%.2f m in a random direction, ±%.3f rad), "
      "%d held-out scans per log, seed %u\n",
      offset_m, offset_rad, scans_per_dataset, seed);
  std::printf("success: within 0.05 m and 0.01 rad of the corrected pose\n\n");
  std::printf(
      "| log | method | success | median error [mm] | median error [mrad] | median time "
      "[ms] | mean time [ms] | converged |\n|---|---|---|---|---|---|---|---|\n");
  for (const std::string name : {"intel", "aces", "fr079"}) {
    if (!only_logs.empty() && only_logs.find("," + name + ",") == std::string::npos) continue;
    const auto samples = ReadCorrectedScans(datasets + "/" + name + ".clf.gz",
                                            datasets + "/" + name + ".corrected-poses.txt");
    PointMap map;  // default de-duplication cell (0.05 m)
    std::vector<const CorrectedScan*> held_out;
    for (std::size_t i = 0; i < samples.size(); ++i) {
      if (i % 2 == 0)
        map.InsertScan(samples[i].scan, samples[i].T_world_laser);
      else
        held_out.push_back(&samples[i]);
    }
    std::vector<const CorrectedScan*> tests;
    const std::size_t n = std::min<std::size_t>(scans_per_dataset, held_out.size());
    for (std::size_t i = 0; i < n; ++i) tests.push_back(held_out[i * held_out.size() / n]);
    std::fprintf(stderr, "%s: %zu corrected scans, map of %zu points, %zu test scans\n",
                 name.c_str(), samples.size(), map.size(), tests.size());
    std::mt19937 rng(seed);
    std::uniform_real_distribution<double> direction(-M_PI, M_PI);
    std::vector<Pose2D> starts;
    for (const CorrectedScan* s : tests) {
      const double a = direction(rng);
      const double yaw = (direction(rng) >= 0.0 ? 1.0 : -1.0) * offset_rad;
      starts.push_back({s->T_world_laser.x_m + offset_m * std::cos(a),
                        s->T_world_laser.y_m + offset_m * std::sin(a),
                        NormalizeAngle(s->T_world_laser.yaw_rad + yaw)});
    }
    const MapView view{nullptr, &map};
    ScoringOptions scoring;
    // Interleaved: every method refines scan i before any refines scan i + 1, so that the load of
    // a shared machine weighs on all methods alike.
    struct Tally {
      std::vector<double> errors_m, errors_rad, times_ms;
      int successes = 0, converged = 0;
    };
    std::vector<Tally> tallies(methods.size());
    for (std::size_t i = 0; i < tests.size(); ++i)
      for (std::size_t m = 0; m < methods.size(); ++m) {
        Tally& t = tallies[m];
        const auto start = std::chrono::steady_clock::now();
        const RefinementResult r = Refine(view, tests[i]->scan, starts[i], scoring,
                                          ValidationOptions{}.alpha_m, methods[m].options);
        t.times_ms.push_back(
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start)
                .count());
        const Pose2D error = Between(tests[i]->T_world_laser, r.T_world_laser);
        const double e_m = std::hypot(error.x_m, error.y_m), e_rad = std::abs(error.yaw_rad);
        t.errors_m.push_back(e_m);
        t.errors_rad.push_back(e_rad);
        t.successes += e_m < 0.05 && e_rad < 0.01;
        t.converged += r.converged;
      }
    for (std::size_t m = 0; m < methods.size(); ++m) {
      const Tally& t = tallies[m];
      double mean_ms = 0.0;
      for (const double v : t.times_ms) mean_ms += v / t.times_ms.size();
      std::printf("| %s | %s | %.0f %% | %.1f | %.2f | %.2f | %.2f | %d/%zu |\n", name.c_str(),
                  methods[m].name.c_str(), 100.0 * t.successes / tests.size(),
                  1e3 * Median(t.errors_m), 1e3 * Median(t.errors_rad), Median(t.times_ms), mean_ms,
                  t.converged, tests.size());
    }
    std::fflush(stdout);
  }
  return 0;
}
