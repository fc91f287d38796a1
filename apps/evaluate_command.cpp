// scanloc evaluate: the relations metric of Kümmerle et al. 2009 for a trajectory.

#include <algorithm>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <vector>

#include "commands.hpp"
#include "evaluate_closures.hpp"
#include "evaluation_frame.hpp"
#include "scanloc/evaluation/relations_evaluation.hpp"
#include "scanloc/io/trajectory.hpp"

namespace scanloc::app {
namespace {

// The time span [first, last] of some timestamps, as text.
template <class Range, class Time>
std::string Span(const Range& items, const Time& time) {
  if (items.empty()) return "none";
  double first = time(items.front()), last = first;
  for (const auto& item : items) {
    first = std::min(first, time(item));
    last = std::max(last, time(item));
  }
  char text[96];
  std::snprintf(text, sizeof text, "%.6f to %.6f s", first, last);
  return text;
}

// The error for an evaluation that matched no relation: both time spans, so that the reader sees
// whether they overlap at all.
std::runtime_error NothingMatched(const std::vector<StampedPose>& trajectory,
                                  const std::vector<Relation>& relations, double tolerance_s) {
  std::vector<double> relation_times;
  for (const Relation& r : relations) relation_times.insert(relation_times.end(), {r.t1_s, r.t2_s});
  return std::runtime_error(
      "no relation matched the trajectory: " + std::to_string(relations.size()) +
      " relations, none with both timestamps within " + std::to_string(tolerance_s) +
      " s of a trajectory pose (trajectory: " + std::to_string(trajectory.size()) + " poses, " +
      Span(trajectory, [](const StampedPose& p) { return p.timestamp_s; }) +
      "; relations: " + Span(relation_times, [](double t) { return t; }) +
      "). Are they from the same log, and is --tolerance large enough?");
}

// The relations metric's counts and statistics, as text or JSON.
void PrintRelationsEvaluation(const RelationsEvaluation& e, const EvaluationFrame& frame,
                              bool json) {
  auto stats = [](const ErrorStatistics& s) {
    return nlohmann::json{{"mean", s.mean}, {"std", s.std}, {"max", s.max}};
  };
  if (json) {
    std::cout << nlohmann::json{{"matched", e.matched},
                                {"unmatched", e.unmatched},
                                {"translation_m", stats(e.translation_m)},
                                {"rotation_deg", stats(e.rotation_deg)},
                                {"translation_squared_m2", stats(e.translation_squared_m2)},
                                {"rotation_squared_deg2", stats(e.rotation_squared_deg2)},
                                {"laser_mounting", ToJson(frame)}}
                     .dump(2)
              << '\n';
    return;
  }
  std::printf("relations: %zu matched, %zu unmatched\n", e.matched, e.unmatched);
  std::printf("scored as the scans' poses: %s\n", Describe(frame).c_str());
  std::printf("translation [m]     %.4f ± %.4f (max %.4f)\n", e.translation_m.mean,
              e.translation_m.std, e.translation_m.max);
  std::printf("translation² [m²]   %.5f ± %.5f (max %.5f)\n", e.translation_squared_m2.mean,
              e.translation_squared_m2.std, e.translation_squared_m2.max);
  std::printf("rotation [deg]      %.3f ± %.3f (max %.3f)\n", e.rotation_deg.mean,
              e.rotation_deg.std, e.rotation_deg.max);
  std::printf("rotation² [deg²]    %.3f ± %.3f (max %.3f)\n", e.rotation_squared_deg2.mean,
              e.rotation_squared_deg2.std, e.rotation_squared_deg2.max);
}

}  // namespace

void RegisterEvaluateCommand(CLI::App& app) {
  struct Arguments {
    std::string trajectory_path, relations_path;
    double tolerance_s = 1e-3;
    bool json = false;
    std::vector<double> mounting;
    ClosureEvaluationArguments closures;
  };
  auto a = std::make_shared<Arguments>();
  CLI::App* command = app.add_subcommand(
      "evaluate",
      "score a TUM trajectory on ground-truth relations (Kümmerle et al. 2009), or a session's "
      "loop closures on reference poses");
  CLI::Option* trajectory_option =
      command->add_option("--trajectory", a->trajectory_path, "TUM trajectory")
          ->check(CLI::ExistingFile);
  CLI::Option* relations_option =
      command->add_option("--relations", a->relations_path, "relations file: t1 t2 x y z r p yaw")
          ->check(CLI::ExistingFile);
  trajectory_option->needs(relations_option);
  relations_option->needs(trajectory_option);
  CLI::Option* closures =
      command
          ->add_option("--closures", a->closures.run_folder,
                       "a session's run folder (loop closure on, the default): score its closures")
          ->check(CLI::ExistingDirectory)
          ->excludes(trajectory_option)
          ->excludes(relations_option);
  CLI::Option* reference =
      command
          ->add_option("--reference", a->closures.reference_path,
                       "reference poses for --closures: t x y theta (corrected poses) or TUM")
          ->check(CLI::ExistingFile);
  closures->needs(reference);
  reference->needs(closures);
  command
      ->add_option("--max-error-m", a->closures.max_error_m,
                   "with --closures: a closure within this and --max-error-deg is right")
      ->check(CLI::PositiveNumber);
  command->add_option("--max-error-deg", a->closures.max_error_deg, "see --max-error-m")
      ->check(CLI::PositiveNumber);
  command->add_option("--tolerance", a->tolerance_s, "timestamp matching tolerance (s)");
  command
      ->add_option("--mounting", a->mounting,
                   "X Y YAW: the laser on the robot whose postures are scored (relations and "
                   "reference poses are the scans'); default: the run's, from summary.json beside "
                   "the trajectory or in the run folder")
      ->expected(3);
  command->add_flag("--json", a->json, "print JSON");
  command->final_callback([a] {
    if (!a->closures.run_folder.empty()) {
      a->closures.tolerance_s = a->tolerance_s;
      a->closures.json = a->json;
      a->closures.mounting = a->mounting;
      return EvaluateRunClosures(a->closures);
    }
    if (a->trajectory_path.empty())
      throw CLI::RequiredError("--trajectory and --relations, or --closures and --reference,");
    const EvaluationFrame frame = ResolveEvaluationFrame(
        a->mounting, std::filesystem::path(a->trajectory_path).parent_path().string());
    const auto trajectory = LaserPoses(ReadTumTrajectory(a->trajectory_path), frame.mounting);
    const auto relations = ReadRelations(a->relations_path);
    RelationsEvaluationOptions options;
    options.timestamp_tolerance_s = a->tolerance_s;
    const RelationsEvaluation e = EvaluateRelations(trajectory, relations, options);
    if (const std::size_t backwards = CountNonIncreasingTimestamps(trajectory); backwards > 0)
      std::cerr << "warning: " << a->trajectory_path << ": " << backwards
                << " timestamps go backwards or repeat the previous one\n";
    if (e.matched == 0) throw NothingMatched(trajectory, relations, a->tolerance_s);
    PrintRelationsEvaluation(e, frame, a->json);
  });
}

}  // namespace scanloc::app
