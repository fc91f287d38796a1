#include "scanloc/session/session.hpp"

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
  require(heading_step_rad > 0.0, "heading_step_rad must be positive");
  require(heading_candidates_min_turn_rad >= 0.0, "heading_candidates_min_turn_rad must be >= 0");
  require(heading_spread_rad / heading_step_rad <= 100.0, "at most 100 heading steps per side");
  require(localise_translation_m >= 0.0 && localise_rotation_rad >= 0.0,
          "localise thresholds must be >= 0");
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
      Pose2D turned = prediction;
      turned.yaw_rad = NormalizeAngle(turned.yaw_rad + offset);
      char label[32];
      std::snprintf(label, sizeof label, "odometry%+.0fdeg", offset * 180.0 / M_PI);
      candidates.push_back({turned, label});
    }
  for (std::size_t i = 0; i < iteration.external_candidates.size(); ++i)
    candidates.push_back({iteration.external_candidates[i], "external" + std::to_string(i)});
  return candidates;
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
    // The best valid candidate; when none is valid, the cheapest by (3.11), flagged below.
    record.chosen = record.candidates.best;
    if (record.chosen < 0) {
      double best_cost = std::numeric_limits<double>::infinity();
      for (std::size_t i = 0; i < record.candidates.candidates.size(); ++i)
        if (record.candidates.candidates[i].cost < best_cost) {
          best_cost = record.candidates.candidates[i].cost;
          record.chosen = static_cast<int>(i);
        }
    }
    if (record.chosen < 0) record.chosen = 0;  // no valid pair anywhere: keep the prediction
    const auto refine_start = std::chrono::steady_clock::now();
    const CandidateEvaluation& chosen = record.candidates.candidates[record.chosen];
    RefinerOptions refiner = refiner_;
    refiner.ceres.score_initial = false;  // the candidate evaluation scored it already
    record.refinement = Refine(map, iteration.scan, chosen.T_world_laser, scoring_, refiner);
    record.refinement->test_before = chosen.test;
    record.refinement->distance_before = chosen.distance;
    record.refine_s = SecondsSince(refine_start);
    // The refined posture must pass rules 1 and 2 on its own.
    const CandidateRanking ranking = RankCandidates({record.refinement->test_after}, validation_);
    record.verdict = ranking.candidates[0].verdict;
    record.validated = record.verdict == Verdict::kValid;
    // A posture the rules do not validate is not trusted over the odometry: the prediction is
    // kept (flagged), so that one bad fit cannot throw the session off.
    record.T_world_robot =
        record.validated ? mounting_.RobotPose(record.refinement->T_world_laser) : prediction;
    if (iteration.odometry) last_localised_odometry_ = *iteration.odometry;
  }

  const bool may_insert = record.validated || (options_.insert_unvalidated && !record.skipped);
  if (may_insert && (!last_inserted_pose_ ||
                     MovedMoreThan(*last_inserted_pose_, record.T_world_robot,
                                   options_.insert_translation_m, options_.insert_rotation_rad))) {
    const auto insert_start = std::chrono::steady_clock::now();
    point_map_.InsertScan(iteration.scan, mounting_.LaserPose(record.T_world_robot));  // (3.6)
    last_inserted_pose_ = record.T_world_robot;
    record.inserted = true;
    record.insert_s = SecondsSince(insert_start);
  }
  if (count_ == 0 && iteration.odometry) last_localised_odometry_ = *iteration.odometry;
  last_pose_ = record.T_world_robot;
  if (iteration.odometry) last_odometry_ = iteration.odometry;
  ++count_;
  record.map_points = point_map_.size();
  record.total_s = SecondsSince(start);
  return record;
}

}  // namespace scanloc
