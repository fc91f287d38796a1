#include "scanloc/refinement/ceres_refiner.hpp"

#include <ceres/ceres.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <stdexcept>
#include <vector>

#include "beam_residuals.hpp"
#include "point_line_fit.hpp"
#include "scanloc/common/parallel_for.hpp"
#include "scanloc/maps/line_map.hpp"
#include "scanloc/maps/point_map.hpp"

namespace scanloc {
namespace {

// Fewer beams than this per core are paired on one thread (a thread costs tens of µs).
constexpr std::size_t kMinBeamsPerThread = 60;

PointLineFitOptions LineFitOptions(const CeresRefinerOptions& options) {
  return {options.line_fit_radius_m, options.line_fit_neighbours, options.max_line_thickness};
}

// `sim_valid`: the simulated scan exists and beam has a hit there.
bool SurfaceLineOfBeam(const MapView& map, const SimulatedScan& sim, std::size_t beam,
                       bool sim_valid, const Eigen::Vector2d& hit, const Eigen::Vector2d& end_point,
                       const CeresRefinerOptions& options, BeamLineFits& fits, SurfaceLine& line) {
  if (sim_valid && sim.hit_source[beam] == HitSource::kSegment) {
    const Segment& s = map.lines->segments[sim.hit_index[beam]];
    const Eigen::Vector2d d = s.b - s.a;
    if (d.norm() < 1e-9) return false;
    line.normal = Eigen::Vector2d(-d.y(), d.x()).normalized();
    line.offset = line.normal.dot(s.a);
    return true;
  }
  if (map.points == nullptr || map.points->empty()) return false;
  if (options.point_association == PointAssociation::kNearestEndpoint)
    return fits.Fit(*map.points, end_point, LineFitOptions(options), line);
  return sim_valid && fits.Fit(*map.points, hit, LineFitOptions(options), line);
}

// A Ceres context shared by every problem this thread builds: without one, each problem
// creates its own.
ceres::Context* SharedContext() {
  thread_local const std::unique_ptr<ceres::Context> context(ceres::Context::Create());
  return context.get();
}

struct BuiltProblem {
  // Owned here rather than by the problem; declared first, destroyed last.
  std::unique_ptr<BeamsResidual> residual;
  std::unique_ptr<PriorResidual> prior;
  ceres::ResidualBlockId beams_block = nullptr;
  std::unique_ptr<ceres::Problem> problem;
  int residual_count = 0;
  std::vector<double> ranges_used_m;
};

BuiltProblem BuildProblem(const MapView& map, const LaserScan& scan, const Pose2D& pose,
                          const SimulatedScan& sim, const ScoringOptions& scoring,
                          const CeresRefinerOptions& options, std::vector<BeamLineFits>& fits,
                          double* parameters) {
  BuiltProblem built;
  ceres::Problem::Options problem_options;
  problem_options.cost_function_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
  // One or two residual blocks (the beams, a prior) on one valid parameter block: the checks
  // would find nothing.
  problem_options.disable_all_safety_checks = true;
  problem_options.context = SharedContext();
  built.problem = std::make_unique<ceres::Problem>(problem_options);
  const double max_residual =
      options.max_residual_m > 0.0 ? options.max_residual_m : scoring.test.match_threshold_m;
  const double min_cos = std::cos(options.max_incidence_rad);
  const bool cosine = options.incidence == IncidenceWeighting::kCosine;
  const bool nearest = options.point_association == PointAssociation::kNearestEndpoint &&
                       map.points != nullptr && !map.points->empty();
  // Without a simulated scan (nearest pairing on a point map needs none) no beam has a hit.
  const bool have_sim = sim.size() == scan.size();
  // Each beam's surface line (a radius search and a fit per beam on point maps: most of the
  // work) over the cores; the residuals are then added in beam order.
  std::vector<std::uint8_t> paired(scan.size(), 0);
  std::vector<SurfaceLine> lines(scan.size());
  ParallelFor(
      scan.size(), kMinBeamsPerThread, [&](std::size_t, std::size_t begin, std::size_t end) {
        for (std::size_t k = begin; k < end; ++k) {
          if (!scan.IsValid(k)) continue;
          const bool sim_valid = have_sim && sim.IsValid(k);
          // Pairs that the Likelihood Test would not count as matches are left out (T_Map's role).
          if (!(sim_valid && std::abs(scan.ranges_m[k] - sim.ranges_m[k]) <= max_residual) &&
              !nearest)
            continue;
          const double phi = pose.yaw_rad + scan.layout.Bearing(k);
          const Eigen::Vector2d u(std::cos(phi), std::sin(phi));
          const Eigen::Vector2d end_point = pose.Translation() + scan.ranges_m[k] * u;
          const Eigen::Vector2d hit =
              pose.Translation() + (sim_valid ? sim.ranges_m[k] : scan.ranges_m[k]) * u;
          SurfaceLine& line = lines[k];
          if (!SurfaceLineOfBeam(map, sim, k, sim_valid, hit, end_point, options, fits[k], line))
            continue;
          if (std::abs(line.normal.dot(end_point) - line.offset) > max_residual) continue;
          const double cos_incidence = std::abs(line.normal.dot(u));
          // Beams that slide along their surface carry no information (and a plain range residual
          // is undefined there); kGate also drops every beam beyond max_incidence_rad.
          if (cos_incidence < 1e-3) continue;
          if (options.incidence == IncidenceWeighting::kGate && cos_incidence < min_cos) continue;
          paired[k] = 1;
        }
      });
  std::vector<BeamTerm> beams;
  const BearingCosines& bearings = BearingCosinesOf(scan.layout);
  for (std::size_t k = 0; k < scan.size(); ++k) {
    if (!paired[k]) continue;
    beams.push_back({bearings.cos[k], bearings.sin[k], scan.ranges_m[k], lines[k]});
    built.ranges_used_m.push_back(scan.ranges_m[k]);
  }
  built.residual_count = static_cast<int>(beams.size());
  if (beams.empty()) return built;
  // The kernels act on s = residual²; with a = c they are the Likelihood Distance's (up to a
  // constant factor).
  built.residual = std::make_unique<BeamsResidual>(
      std::move(beams), cosine, BeamKernel(scoring.distance.kernel, scoring.distance.scale_m));
  built.beams_block = built.problem->AddResidualBlock(built.residual.get(), nullptr, parameters);
  if (options.prior) {
    built.prior = std::make_unique<PriorResidual>(
        options.prior->mean, scoring.distance.scale_m * options.prior->inverse_sigma);
    built.problem->AddResidualBlock(built.prior.get(), nullptr, parameters);
  }
  return built;
}

// Covariance σ²·(JᵀJ)⁻¹ and a degeneracy verdict from the information matrix JᵀJ at the solution.
void EstimateUncertainty(BuiltProblem& built, const CeresRefinerOptions& options,
                         RefinementResult& result) {
  if (built.residual_count < 4) {
    result.degenerate = true;
    result.degeneracy =
        "too few beams constrain the posture (" + std::to_string(built.residual_count) + ")";
    return;
  }
  double cost = 0.0;
  ceres::CRSMatrix jacobian;
  ceres::Problem::EvaluateOptions evaluate;
  evaluate.residual_blocks = {built.beams_block};  // the scan's evidence, without the prior
  built.problem->Evaluate(evaluate, &cost, nullptr, nullptr, &jacobian);
  Eigen::Matrix3d information = Eigen::Matrix3d::Zero();
  for (int row = 0; row < jacobian.num_rows; ++row) {
    Eigen::Vector3d j = Eigen::Vector3d::Zero();
    for (int i = jacobian.rows[row]; i < jacobian.rows[row + 1]; ++i)
      j(jacobian.cols[i]) = jacobian.values[i];
    information += j * j.transpose();
  }
  // Compare translation and rotation in one unit: a turn δθ moves points at the median range by
  // median·δθ metres.
  std::vector<double>& ranges = built.ranges_used_m;
  std::nth_element(ranges.begin(), ranges.begin() + ranges.size() / 2, ranges.end());
  const double lever_m = std::max(0.1, ranges[ranges.size() / 2]);
  const Eigen::Vector3d scale(1.0, 1.0, 1.0 / lever_m);
  const Eigen::Matrix3d scaled = scale.asDiagonal() * information * scale.asDiagonal();
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> eigen(scaled);
  const double weakest = eigen.eigenvalues()(0), strongest = eigen.eigenvalues()(2);
  if (!(strongest > 0.0) || weakest < options.degeneracy_ratio * strongest) {
    result.degenerate = true;
    const Eigen::Vector3d v = eigen.eigenvectors().col(0);
    char text[160];
    if (v.head<2>().norm() >= std::abs(v(2)))
      std::snprintf(text, sizeof text,
                    "translation along (%.2f, %.2f) in the world is poorly constrained "
                    "(information ratio %.2g)",
                    v(0) / v.head<2>().norm(), v(1) / v.head<2>().norm(),
                    strongest > 0.0 ? weakest / strongest : 0.0);
    else
      std::snprintf(text, sizeof text, "rotation is poorly constrained (information ratio %.2g)",
                    strongest > 0.0 ? weakest / strongest : 0.0);
    result.degeneracy = text;
  }
  const double sigma2 = 2.0 * cost / std::max(1, built.residual_count - 3);
  const Eigen::FullPivLU<Eigen::Matrix3d> lu(information);
  if (lu.isInvertible()) {
    result.covariance = sigma2 * lu.inverse();
    result.has_covariance = true;
  }
}

// One outer iteration's Levenberg–Marquardt solve from `parameters`; the posture it returns.
Pose2D Solve(BuiltProblem& built, const CeresRefinerOptions& options, double* parameters) {
  ceres::Solver::Options solver_options;
  solver_options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
  solver_options.max_num_iterations = options.max_solver_iterations;
  solver_options.num_threads = 1;
  solver_options.logging_type = ceres::SILENT;
  ceres::Solver::Summary summary;
  ceres::Solve(solver_options, built.problem.get(), &summary);
  return {parameters[0], parameters[1], NormalizeAngle(parameters[2])};
}

// Where the cap leaves outer iterations that cycle: the solve after visited.back() returned
// visited[first] (first ≥ `from`), so the iteration that starts from visited.size() starts from
// visited[first] again, and iteration i ≥ first from visited[first + (i − first) mod period].
struct CycleShortcut {
  bool found = false;
  std::size_t final_posture = 0;  // index in visited of the posture the cap's run ends at
  std::size_t last_start = 0;     // ... and of the posture its last iteration started from
  std::size_t period = 0;
};

CycleShortcut FindCycle(const std::vector<Pose2D>& visited, std::size_t from, const Pose2D& next,
                        int cap) {
  CycleShortcut cycle;
  const auto same = [&](const Pose2D& p) { return SamePosture(p, next); };
  const auto first = static_cast<std::size_t>(
      std::find_if(visited.begin() + std::min(from, visited.size()), visited.end(), same) -
      visited.begin());
  const auto n = static_cast<std::size_t>(cap);
  if (first == visited.size() || n <= visited.size()) return cycle;
  const std::size_t period = visited.size() - first;
  cycle.found = true;
  cycle.period = period;
  cycle.final_posture = first + (n - first) % period;
  cycle.last_start = first + (n - 1 - first) % period;
  return cycle;
}

}  // namespace

const char* ToString(IncidenceWeighting weighting) {
  switch (weighting) {
    case IncidenceWeighting::kNone:
      return "none";
    case IncidenceWeighting::kCosine:
      return "cosine";
    case IncidenceWeighting::kGate:
      return "gate";
  }
  return "?";
}

const char* ToString(PointAssociation association) {
  return association == PointAssociation::kSimulatedHit ? "simulated-hit" : "nearest-endpoint";
}

PointAssociation ParsePointAssociation(const std::string& name) {
  if (name == "simulated-hit") return PointAssociation::kSimulatedHit;
  if (name == "nearest-endpoint") return PointAssociation::kNearestEndpoint;
  throw std::invalid_argument("unknown point association '" + name +
                              "' (expected simulated-hit or nearest-endpoint)");
}

IncidenceWeighting ParseIncidenceWeighting(const std::string& name) {
  if (name == "none") return IncidenceWeighting::kNone;
  if (name == "cosine") return IncidenceWeighting::kCosine;
  if (name == "gate") return IncidenceWeighting::kGate;
  throw std::invalid_argument("unknown incidence weighting '" + name +
                              "' (expected none, cosine or gate)");
}

void CeresRefinerOptions::Validate() const {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("CeresRefinerOptions: ") + what);
  };
  require(max_outer_iterations >= 1, "max_outer_iterations must be >= 1");
  require(max_solver_iterations >= 1, "max_solver_iterations must be >= 1");
  require(translation_tolerance_m > 0.0 && rotation_tolerance_rad > 0.0,
          "tolerances must be positive");
  require(max_incidence_rad > 0.0 && max_incidence_rad < M_PI / 2,
          "max_incidence_rad must be in (0, π/2)");
  require(std::isfinite(max_residual_m), "max_residual_m must be finite");
  require(line_fit_neighbours >= 2, "line_fit_neighbours must be >= 2");
  require(line_fit_radius_m > 0.0, "line_fit_radius_m must be positive");
  require(max_line_thickness > 0.0 && max_line_thickness <= 1.0,
          "max_line_thickness must be in (0, 1]");
  require(degeneracy_ratio >= 0.0 && degeneracy_ratio < 1.0, "degeneracy_ratio must be in [0, 1)");
  require(
      !prior || (prior->inverse_sigma.allFinite() && (prior->inverse_sigma.array() >= 0.0).all()),
      "a prior's inverse σ must be finite and >= 0");
}

RefinementResult RefineCeres(const MapView& map, const LaserScan& scan,
                             const Pose2D& T_world_laser_initial, const ScoringOptions& scoring,
                             const CeresRefinerOptions& options) {
  options.Validate();
  scan.CheckConsistent();
  const auto start = std::chrono::steady_clock::now();
  RefinementResult result;
  PostureScore score;
  const bool needs_simulation = (map.lines != nullptr && !map.lines->empty()) ||
                                options.point_association == PointAssociation::kSimulatedHit;
  if (options.score_initial || needs_simulation) {
    score = ScorePosture(map, scan, T_world_laser_initial, scoring);
    result.test_before = score.test;
    result.distance_before = score.distance;
  }
  Pose2D pose = T_world_laser_initial;
  // With nearest-end-point pairing on a point-only map, correspondences need no simulated scan:
  // the scan is simulated only to score the postures before and after.
  SimulatedScan simulated = score.simulated;
  // Each beam's line fits over the outer iterations (and the final problem), exactly as fitted
  // afresh; kept per thread so that their buffers are reused from one refinement to the next.
  thread_local std::vector<BeamLineFits> fits;
  fits.resize(scan.size());
  for (BeamLineFits& beam : fits) beam.Reset();
  BuiltProblem built;
  // Outlives the loop: the last problem is evaluated at the solution for the uncertainty.
  double parameters[3] = {pose.x_m, pose.y_m, pose.yaw_rad};
  // The posture each outer iteration started from: an outer iteration is a function of it alone
  // (its correspondences, then a deterministic solve).
  std::vector<Pose2D> visited;
  const auto build_at = [&](const Pose2D& at, int outer) {
    if (outer > 0 && needs_simulation)
      simulated = Simulate(map, scan.layout, at, scoring.simulation);
    parameters[0] = at.x_m;
    parameters[1] = at.y_m;
    parameters[2] = at.yaw_rad;
    built = BuildProblem(map, scan, at, simulated, scoring, options, fits, parameters);
  };
  for (int outer = 0; outer < options.max_outer_iterations; ++outer) {
    build_at(pose, outer);
    visited.push_back(pose);
    result.iterations = outer + 1;
    if (built.residual_count < 3) break;
    const Pose2D next = Solve(built, options, parameters);
    const Pose2D step = Between(pose, next);
    pose = next;
    if (std::hypot(step.x_m, step.y_m) < options.translation_tolerance_m &&
        std::abs(step.yaw_rad) < options.rotation_tolerance_rad) {
      result.converged = true;
      break;
    }
    // A posture an earlier iteration started from: the iterations cycle from there on, and the
    // cap's posture and last problem are known without running them (the same, bit for bit).
    // (The first iteration pairs with the scoring's simulated scan: with simulation it is not
    // counted in a cycle.)
    const CycleShortcut cycle =
        FindCycle(visited, needs_simulation ? 1 : 0, next, options.max_outer_iterations);
    if (!cycle.found) continue;
    pose = visited[cycle.final_posture];
    result.iterations = options.max_outer_iterations;
    result.cycle_period = static_cast<int>(cycle.period);
    if (cycle.last_start != visited.size() - 1)
      build_at(visited[cycle.last_start], options.max_outer_iterations - 1);
    break;
  }
  score = ScorePosture(map, scan, pose, scoring);
  result.T_world_laser = pose;
  result.test_after = score.test;
  result.distance_after = score.distance;
  // The uncertainty of the final posture, from the last problem (the correspondences the posture
  // was found with) evaluated at the solution.
  if (!built.problem) {
    built = BuildProblem(map, scan, pose, score.simulated, scoring, options, fits, parameters);
  } else {
    parameters[0] = pose.x_m;
    parameters[1] = pose.y_m;
    parameters[2] = pose.yaw_rad;
  }
  EstimateUncertainty(built, options, result);
  result.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace scanloc
