// scanloc test: the Likelihood Test of every candidate posture, as the chapter's tables.

#include <fstream>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "common_options.hpp"
#include "scanloc/io/candidate_report.hpp"
#include "scanloc/io/candidates_file.hpp"
#include "scanloc/io/scan_file.hpp"
#include "scanloc/session/localisation.hpp"

namespace scanloc::app {

void RegisterTestCommand(CLI::App& app) {
  struct Arguments {
    MapArguments map;
    ConfigArguments config;
    std::string scan_path, candidates_path;
    std::size_t scan_index = 0;
    bool json = false;
  };
  auto arguments = std::make_shared<Arguments>();
  CLI::App* command = app.add_subcommand(
      "test", "Likelihood Test of candidate postures: moments, histogram, validity and rank");
  arguments->map.Register(*command);
  arguments->config.Register(*command);
  command->add_option("--scan", arguments->scan_path, "scan file, or CARMEN log (.clf[.gz])")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--scan-index", arguments->scan_index, "which scan of a CARMEN log (0-based)")
      ->check(NonNegativeInteger());
  command->add_option("--candidates", arguments->candidates_path, "'x y theta [label]' per line")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_flag("--json", arguments->json, "print JSON (with histograms) instead of a table");
  command->final_callback([arguments] {
    const Config config = arguments->config.Build();
    const LoadedMaps maps = LoadMaps(arguments->map, config);
    const LaserScan scan = LoadScan(arguments->scan_path, arguments->scan_index, config.log);
    const auto candidates = ReadCandidatesFile(arguments->candidates_path);
    const LocalisationResult result =
        Localise(maps.View(), scan, candidates, config.mounting,
                 {config.scoring, config.validation, config.refiner}, RefinePolicy::kNone);
    if (arguments->json) {
      nlohmann::json out = EvaluatedToJson(result);
      out["config"] = ToJson(config);
      std::cout << out.dump(2) << '\n';
    } else {
      PrintCandidateTable(std::cout, result);
    }
  });
}

}  // namespace scanloc::app
