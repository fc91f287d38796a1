#include "scanloc/refinement/error_descent.hpp"

#include <array>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <map>
#include <stdexcept>
#include <string>
#include <vector>

#include "scanloc/likelihood/candidate_ranking.hpp"

namespace scanloc {
namespace {

constexpr int kMaxStepLevels = 30;  // keeps the lattice strides 2^(levels−1) within 32 bits
// Costs closer than this are a tie (they come from integer histograms, so equal histograms give
// equal costs up to rounding in the division).
constexpr double kCostTieTolerance = 1e-12;

void Require(bool condition, const std::string& message) {
  if (!condition) throw std::invalid_argument("ErrorDescentOptions: " + message);
}

// Postures are visited on a lattice around the initial one whose unit is the last level's step:
// a level's step is a power-of-two multiple of it, so a posture reached at any level has exact
// integer coordinates and is scored once however often the search comes back to it.
using LatticeKey = std::array<std::int64_t, 3>;  // (x, y, θ) in units of the finest step

struct Evaluation {
  double cost = 0.0;  // (3.11)
  LikelihoodTestResult test;
  LikelihoodDistanceResult distance;
};

// (3.11) cost first; on a tie, the lower (3.10) dispersion. A posture without valid pairs has an
// infinite cost and never improves on anything.
bool Improves(const Evaluation& a, const Evaluation& b) {
  if (a.cost < b.cost - kCostTieTolerance) return true;
  if (std::abs(a.cost - b.cost) <= kCostTieTolerance)
    return a.test.dispersion_m2 < b.test.dispersion_m2;
  return false;
}

// Offsets of the neighbours one step away: the 6 axis moves, or the 26 of the 3×3×3 stencil.
std::vector<LatticeKey> NeighbourOffsets(bool diagonal_moves) {
  std::vector<LatticeKey> offsets;
  for (std::int64_t dx = -1; dx <= 1; ++dx)
    for (std::int64_t dy = -1; dy <= 1; ++dy)
      for (std::int64_t dt = -1; dt <= 1; ++dt) {
        const int moved_axes = (dx != 0) + (dy != 0) + (dt != 0);
        if (moved_axes == 0 || (!diagonal_moves && moved_axes > 1)) continue;
        offsets.push_back({dx, dy, dt});
      }
  return offsets;
}

class LatticeSearch {
 public:
  LatticeSearch(const MapView& map, const LaserScan& scan, const Pose2D& T_world_laser_initial,
                const ScoringOptions& scoring, double alpha_m, const ErrorDescentOptions& options)
      : map_(map),
        scan_(scan),
        initial_(T_world_laser_initial),
        scoring_(scoring),
        alpha_m_(alpha_m),
        unit_m_(std::ldexp(options.initial_step_m, 1 - options.step_levels)),
        unit_rad_(std::ldexp(options.initial_step_rad, 1 - options.step_levels)) {}

  // Steps are taken along the world axes and the heading, as in the chapter's (±x, ±y, ±θ).
  Pose2D PoseAt(const LatticeKey& key) const {
    return Pose2D(initial_.x_m + key[0] * unit_m_, initial_.y_m + key[1] * unit_m_,
                  NormalizeAngle(initial_.yaw_rad + key[2] * unit_rad_));
  }

  const Evaluation& Evaluate(const LatticeKey& key) {
    auto found = cache_.find(key);
    if (found != cache_.end()) return found->second;
    const PostureScore score = ScorePosture(map_, scan_, PoseAt(key), scoring_);
    Evaluation evaluation;
    evaluation.cost = LikelihoodCost(score.test, alpha_m_);
    evaluation.test = score.test;
    evaluation.distance = score.distance;
    return cache_.emplace(key, std::move(evaluation)).first->second;
  }

  int postures_scored() const { return static_cast<int>(cache_.size()); }

 private:
  const MapView& map_;
  const LaserScan& scan_;
  Pose2D initial_;
  const ScoringOptions& scoring_;
  double alpha_m_;
  double unit_m_, unit_rad_;
  std::map<LatticeKey, Evaluation> cache_;
};

}  // namespace

void ErrorDescentOptions::Validate() const {
  Require(std::isfinite(initial_step_m) && initial_step_m > 0.0,
          "initial_step_m must be positive and finite");
  Require(std::isfinite(initial_step_rad) && initial_step_rad > 0.0,
          "initial_step_rad must be positive and finite");
  Require(step_levels >= 1 && step_levels <= kMaxStepLevels,
          "step_levels must be in [1, " + std::to_string(kMaxStepLevels) + "]");
  Require(max_moves_per_level >= 1, "max_moves_per_level must be >= 1");
}

RefinementResult RefineErrorDescent(const MapView& map, const LaserScan& scan,
                                    const Pose2D& T_world_laser_initial,
                                    const ScoringOptions& scoring, double alpha_m,
                                    const ErrorDescentOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  options.Validate();
  if (!(std::isfinite(alpha_m) && alpha_m >= 0.0))
    throw std::invalid_argument("RefineErrorDescent: alpha_m must be finite and >= 0");
  scan.CheckConsistent();
  if (!std::isfinite(T_world_laser_initial.x_m) || !std::isfinite(T_world_laser_initial.y_m) ||
      !std::isfinite(T_world_laser_initial.yaw_rad))
    throw std::invalid_argument("RefineErrorDescent: the initial posture must be finite");

  LatticeSearch search(map, scan, T_world_laser_initial, scoring, alpha_m, options);
  const std::vector<LatticeKey> offsets = NeighbourOffsets(options.diagonal_moves);

  RefinementResult result;
  LatticeKey current{0, 0, 0};
  const Evaluation& initial = search.Evaluate(current);
  result.test_before = initial.test;
  result.distance_before = initial.distance;
  // Nothing to compare (empty map view, all-invalid scan, map out of range): no descent.
  const bool comparable = initial.test.valid_pairs > 0;
  bool budget_exhausted = false;  // some level was still improving after max_moves_per_level

  for (int level = 0; comparable && level < options.step_levels; ++level) {
    const std::int64_t stride = std::int64_t{1} << (options.step_levels - 1 - level);
    bool improving = true;
    for (int moves = 0; improving && moves < options.max_moves_per_level; ++moves) {
      LatticeKey best_key = current;
      const Evaluation* best = &search.Evaluate(current);
      for (const LatticeKey& offset : offsets) {
        const LatticeKey key{current[0] + stride * offset[0], current[1] + stride * offset[1],
                             current[2] + stride * offset[2]};
        const Evaluation& neighbour = search.Evaluate(key);
        if (Improves(neighbour, *best)) {
          best = &neighbour;
          best_key = key;
        }
      }
      improving = best_key != current;  // when no neighbour improves, the step halves
      current = best_key;
    }
    budget_exhausted = budget_exhausted || improving;
  }

  const Evaluation& final_evaluation = search.Evaluate(current);
  result.T_world_laser = search.PoseAt(current);
  result.test_after = final_evaluation.test;
  result.distance_after = final_evaluation.distance;
  result.iterations = search.postures_scored();
  result.converged = comparable && !budget_exhausted;
  result.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace scanloc
