// scanloc compare: one sequence with ground truth localised against the line map, against a point
// map grown from nothing and against both, each measured against the truth; or, with --runs, run
// folders of `session` and `localise` set side by side (e.g. localise on a line map and on a scan
// map of the same place).

#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "common_options.hpp"
#include "scanloc/evaluation/mode_comparison.hpp"
#include "scanloc/report/run_comparison.hpp"

namespace scanloc::app {
namespace {

nlohmann::json ToJson(const ModeResult& r) {
  nlohmann::json row = {{"mode", ToString(r.mode)},
                        {"iterations", r.iterations},
                        {"localised", r.localised},
                        {"validated", r.validated},
                        {"with_truth", r.with_truth},
                        {"mean_match_pairs", r.mean_match_pairs},
                        {"mean_valid_pairs", r.mean_valid_pairs},
                        {"mean_match_ratio", r.mean_match_ratio},
                        {"mean_expect_value_m", r.mean_expect_value_m},
                        {"mean_iteration_s", r.mean_iteration_s},
                        {"map_points", r.map_points}};
  if (r.with_truth > 0) {
    row["mean_translation_error_m"] = r.mean_translation_error_m;
    row["max_translation_error_m"] = r.max_translation_error_m;
    row["mean_rotation_error_rad"] = r.mean_rotation_error_rad;
    row["max_rotation_error_rad"] = r.max_rotation_error_rad;
  }
  return row;
}

}  // namespace

void RegisterCompareCommand(CLI::App& app) {
  struct Arguments {
    std::string sequence_path;
    std::vector<std::string> line_map_paths;
    std::vector<std::string> runs;
    std::vector<std::string> modes{"lines", "points", "both"};
    std::size_t max_iterations = 0;
    bool json = false;
    ConfigArguments config;
  };
  auto a = std::make_shared<Arguments>();
  CLI::App* command = app.add_subcommand(
      "compare",
      "localise a sequence with ground truth against the line map, a point map grown from "
      "nothing, and both; print each mode's validation rate, error against the truth, moments "
      "and time (or, with --runs, set run folders side by side)");
  auto* sequence_option =
      command->add_option("--sequence", a->sequence_path, "native sequence with truth (.seq.jsonl)")
          ->check(CLI::ExistingFile);
  auto* line_map_option =
      command
          ->add_option("--line-map", a->line_map_paths,
                       "line map; several files make one map (e.g. office.lines blinds.lines)")
          ->check(CLI::ExistingFile);
  auto* runs_option =
      command
          ->add_option("--runs", a->runs,
                       "run folders of `session` or `localise` to set side by side; the "
                       "postures of each are measured against the first's")
          ->check(CLI::ExistingDirectory)
          ->excludes(sequence_option)
          ->excludes(line_map_option);
  sequence_option->needs(line_map_option);
  command
      ->add_option("--modes", a->modes, "modes to run, in order: lines, points, both (default all)")
      ->delimiter(',')
      ->check(CLI::IsMember({"lines", "points", "both"}));
  command->add_option("--max-iterations", a->max_iterations, "stop after this many (0: all)");
  command->add_flag("--json", a->json, "print one JSON object per mode instead of the table");
  a->config.Register(*command);
  command->final_callback([a, runs_option] {
    if (runs_option->count() > 0) {
      PrintRunComparison(std::cout, CompareRuns(a->runs));
      return;
    }
    if (a->sequence_path.empty() || a->line_map_paths.empty())
      throw CLI::ValidationError("compare", "--sequence and --line-map, or --runs, are required");
    const Config config = a->config.Build();
    LineMap line_map;
    for (const auto& path : a->line_map_paths) {
      const LineMap part = ReadLineMap(path);
      line_map.segments.insert(line_map.segments.end(), part.segments.begin(), part.segments.end());
    }
    std::vector<ModeResult> results;
    for (const auto& mode : a->modes) {
      results.push_back(
          RunMode(ParseMapMode(mode), a->sequence_path, line_map, config, a->max_iterations));
      if (a->json) std::cout << ToJson(results.back()).dump() << '\n';
    }
    if (a->json) return;
    std::cout << "compare: " << a->sequence_path << ", line map of " << line_map.segments.size()
              << " segments; errors against the truth, moments of the refined posture\n";
    PrintComparison(std::cout, results);
  });
}

}  // namespace scanloc::app
