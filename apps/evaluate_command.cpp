// scanloc evaluate: the relations metric of Kümmerle et al. 2009 for a trajectory.

#include <cstdio>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "scanloc/evaluation/relations_evaluation.hpp"
#include "scanloc/io/trajectory.hpp"

namespace scanloc::app {

void RegisterEvaluateCommand(CLI::App& app) {
  struct Arguments {
    std::string trajectory_path, relations_path;
    double tolerance_s = 1e-3;
    bool json = false;
  };
  auto a = std::make_shared<Arguments>();
  CLI::App* command = app.add_subcommand(
      "evaluate", "score a TUM trajectory on ground-truth relations (Kümmerle et al. 2009)");
  command->add_option("--trajectory", a->trajectory_path, "TUM trajectory")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--relations", a->relations_path, "relations file: t1 t2 x y z r p yaw")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--tolerance", a->tolerance_s, "timestamp matching tolerance (s)");
  command->add_flag("--json", a->json, "print JSON");
  command->final_callback([a] {
    const auto trajectory = ReadTumTrajectory(a->trajectory_path);
    const auto relations = ReadRelations(a->relations_path);
    RelationsEvaluationOptions options;
    options.timestamp_tolerance_s = a->tolerance_s;
    const RelationsEvaluation e = EvaluateRelations(trajectory, relations, options);
    auto stats = [](const ErrorStatistics& s) {
      return nlohmann::json{{"mean", s.mean}, {"std", s.std}, {"max", s.max}};
    };
    if (a->json) {
      std::cout << nlohmann::json{{"matched", e.matched},
                                  {"unmatched", e.unmatched},
                                  {"translation_m", stats(e.translation_m)},
                                  {"rotation_deg", stats(e.rotation_deg)},
                                  {"translation_squared_m2", stats(e.translation_squared_m2)},
                                  {"rotation_squared_deg2", stats(e.rotation_squared_deg2)}}
                       .dump(2)
                << '\n';
      return;
    }
    std::printf("relations: %zu matched, %zu unmatched\n", e.matched, e.unmatched);
    std::printf("translation [m]     %.4f ± %.4f (max %.4f)\n", e.translation_m.mean,
                e.translation_m.std, e.translation_m.max);
    std::printf("translation² [m²]   %.5f ± %.5f (max %.5f)\n", e.translation_squared_m2.mean,
                e.translation_squared_m2.std, e.translation_squared_m2.max);
    std::printf("rotation [deg]      %.3f ± %.3f (max %.3f)\n", e.rotation_deg.mean,
                e.rotation_deg.std, e.rotation_deg.max);
    std::printf("rotation² [deg²]    %.3f ± %.3f (max %.3f)\n", e.rotation_squared_deg2.mean,
                e.rotation_squared_deg2.std, e.rotation_squared_deg2.max);
  });
}

}  // namespace scanloc::app
