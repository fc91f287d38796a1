#include "scanloc/session/session.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace scanloc {
namespace {

double SecondsSince(std::chrono::steady_clock::time_point start) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
}

}  // namespace

void SessionOptions::Validate() const {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("SessionOptions: ") + what);
  };
  require(heading_spread_rad >= 0.0 && heading_spread_rad < M_PI, "heading_spread_rad in [0, π)");
  require(max_refined_candidates >= 1, "max_refined_candidates must be >= 1");
  require(heading_step_rad > 0.0, "heading_step_rad must be positive");
  require(heading_candidates_min_turn_rad >= 0.0, "heading_candidates_min_turn_rad must be >= 0");
  require(heading_spread_rad / heading_step_rad <= 100.0, "at most 100 heading steps per side");
  require(localise_translation_m >= 0.0 && localise_rotation_rad >= 0.0,
          "localise thresholds must be >= 0");
  require(free_space_margin_m >= 0.0, "free_space_margin_m must be >= 0");
  require(free_space_margin_per_m >= 0.0 && free_space_margin_per_m < 1.0,
          "free_space_margin_per_m must be in [0, 1)");
  require(insert_translation_m >= 0.0 && insert_rotation_rad >= 0.0,
          "insert thresholds must be >= 0");
  require(std::isfinite(initial_pose.x_m) && std::isfinite(initial_pose.y_m) &&
              std::isfinite(initial_pose.yaw_rad),
          "initial_pose must be finite");
}

Session::Session(SessionOptions options, ScoringOptions scoring, ValidationOptions validation,
                 RefinerOptions refiner, LaserMounting mounting, LineMap line_map,
                 PointMap point_map)
    : options_(options),
      scoring_(scoring),
      validation_(validation),
      refiner_(refiner),
      mounting_(mounting),
      line_map_(std::move(line_map)),
      point_map_(std::move(point_map)) {
  options_.Validate();
  validation_.Validate();
  scoring_.test.Validate();
  scoring_.distance.Validate();
}

bool Session::MovedMoreThan(const Pose2D& from, const Pose2D& to, double translation_m,
                            double rotation_rad) const {
  const Pose2D delta = Between(from, to);
  return std::hypot(delta.x_m, delta.y_m) > translation_m || std::abs(delta.yaw_rad) > rotation_rad;
}

std::vector<Candidate> Session::MakeCandidates(const Pose2D& prediction, const Iteration& iteration,
                                               bool turning) const {
  std::vector<Candidate> candidates{{prediction, "odometry"}};
  const int steps = !turning ? 0
                             : static_cast<int>(std::floor(
                                   options_.heading_spread_rad / options_.heading_step_rad + 1e-3));
  for (int s = 1; s <= steps; ++s)
    for (const int sign : {-1, 1}) {
      const double offset = sign * s * options_.heading_step_rad;
      // Turned about the laser, so that all share its position (and one simulated sweep).
      Pose2D turned = mounting_.LaserPose(prediction);
      turned.yaw_rad = NormalizeAngle(turned.yaw_rad + offset);
      char label[32];
      std::snprintf(label, sizeof label, "odometry%+.0fdeg", offset * 180.0 / M_PI);
      candidates.push_back({mounting_.RobotPose(turned), label});
    }
  for (std::size_t i = 0; i < iteration.external_candidates.size(); ++i)
    candidates.push_back({iteration.external_candidates[i], "external" + std::to_string(i)});
  return candidates;
}

std::vector<int> Session::CandidatesToRefine(const CandidateEvaluationResult& evaluated) const {
  // The valid candidates by rank; when none is valid, the cheapest by (3.11) alone.
  std::vector<int> order;
  const auto& candidates = evaluated.candidates;
  for (std::size_t i = 0; i < candidates.size(); ++i)
    if (candidates[i].rank >= 0) order.push_back(static_cast<int>(i));
  std::sort(order.begin(), order.end(),
            [&](int a, int b) { return candidates[a].rank < candidates[b].rank; });
  if (static_cast<int>(order.size()) > options_.max_refined_candidates)
    order.resize(options_.max_refined_candidates);
  if (order.empty() && !candidates.empty()) {
    int cheapest = 0;
    for (std::size_t i = 1; i < candidates.size(); ++i)
      if (candidates[i].cost < candidates[cheapest].cost) cheapest = static_cast<int>(i);
    order.push_back(cheapest);
  }
  return order;
}

IterationRecord Session::Process(const Iteration& iteration) {
  const auto start = std::chrono::steady_clock::now();
  iteration.scan.CheckConsistent();
  IterationRecord record;
  record.index = count_;
  record.timestamp_s = iteration.timestamp_s;
  record.origin = iteration.origin;
  const MapView map{line_map_.empty() ? nullptr : &line_map_, &point_map_};

  // The odometry prediction: the previous posture moved by the odometry increment.
  Pose2D prediction = count_ == 0 ? options_.initial_pose : last_pose_;
  if (count_ > 0 && iteration.odometry && last_odometry_)
    prediction = last_pose_ * Between(*last_odometry_, *iteration.odometry);
  record.prediction = prediction;

  const bool map_empty = map.empty();
  const bool moved = count_ == 0 || !iteration.odometry ||
                     MovedMoreThan(last_localised_odometry_, *iteration.odometry,
                                   options_.localise_translation_m, options_.localise_rotation_rad);
  if (map_empty && iteration.external_candidates.empty()) {
    // Nothing to localise against: the posture is the prediction (the origin at first, §3.2.2).
    record.first = count_ == 0;
    record.T_world_robot = prediction;
    record.validated = record.first;
    record.verdict = record.first ? Verdict::kValid : Verdict::kNoValidPairs;
  } else if (!moved && iteration.external_candidates.empty()) {
    record.skipped = true;
    record.T_world_robot = prediction;
    record.validated = false;
  } else {
    const auto evaluate_start = std::chrono::steady_clock::now();
    const bool turning = !iteration.odometry ||
                         std::abs(Between(last_localised_odometry_, *iteration.odometry).yaw_rad) >
                             options_.heading_candidates_min_turn_rad;
    record.candidates =
        EvaluateCandidates(map, iteration.scan, MakeCandidates(prediction, iteration, turning),
                           mounting_, scoring_, validation_);
    record.evaluate_s = SecondsSince(evaluate_start);
    record.refine_s = 0.0;
    const auto refine_start = std::chrono::steady_clock::now();
    RefinerOptions refiner = refiner_;
    refiner.ceres.score_initial = false;  // the candidate evaluation scored them already
    std::vector<LikelihoodTestResult> tests;
    for (const int i : CandidatesToRefine(record.candidates)) {
      const CandidateEvaluation& candidate = record.candidates.candidates[i];
      IterationRecord::Refined refined;
      refined.candidate = i;
      refined.refinement = Refine(map, iteration.scan, candidate.T_world_laser, scoring_,
                                  validation_.alpha_m, refiner);
      refined.refinement.test_before = candidate.test;
      refined.refinement.distance_before = candidate.distance;
      tests.push_back(refined.refinement.test_after);
      record.refined.push_back(std::move(refined));
    }
    record.refine_s = SecondsSince(refine_start);
    // The refined postures are ranked by the rules; the best valid one is kept. When none is
    // valid, the one with the lowest cost (3.11) is the best guess, flagged.
    const int best = RankInto(tests, validation_, record.refined);
    int kept = best;
    if (kept < 0) {
      double best_cost = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < record.refined.size(); ++i) {
        if (record.refined[i].cost < best_cost) {
          best_cost = record.refined[i].cost;
          kept = static_cast<int>(i);
        }
      }
    }
    if (kept < 0) kept = 0;
    const IterationRecord::Refined& chosen = record.refined[kept];
    record.chosen = chosen.candidate;
    record.refinement = chosen.refinement;
    record.verdict = chosen.verdict;
    record.validated = best >= 0;
    // A posture the rules do not validate is still the best guess (flagged): keeping the
    // odometry instead would carry its heading error in fast turns into every later scan.
    record.T_world_robot = mounting_.RobotPose(record.refinement->T_world_laser);
    if (iteration.odometry) last_localised_odometry_ = *iteration.odometry;
  }

  const bool may_insert = record.validated || (options_.insert_unvalidated && !record.skipped);
  if (may_insert && (!last_inserted_pose_ ||
                     MovedMoreThan(*last_inserted_pose_, record.T_world_robot,
                                   options_.insert_translation_m, options_.insert_rotation_rad))) {
    const auto insert_start = std::chrono::steady_clock::now();
    const Pose2D T_world_laser = mounting_.LaserPose(record.T_world_robot);
    if (options_.free_space_margin_m > 0.0)
      record.carved =
          point_map_.CarveFreeSpace(iteration.scan, T_world_laser, options_.free_space_margin_m,
                                    options_.free_space_margin_per_m);
    point_map_.InsertScan(iteration.scan, T_world_laser);  // (3.6)
    last_inserted_pose_ = record.T_world_robot;
    record.inserted = true;
    record.insert_s = SecondsSince(insert_start);
  }
  if (count_ == 0 && iteration.odometry) last_localised_odometry_ = *iteration.odometry;
  last_pose_ = record.T_world_robot;
  if (iteration.odometry) last_odometry_ = iteration.odometry;
  ++count_;
  record.map_points = point_map_.live_size();
  record.total_s = SecondsSince(start);
  return record;
}

}  // namespace scanloc
