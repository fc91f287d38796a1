// scanloc refine: every candidate before and after refinement, as the chapter's Tables 2, 5, 6, 8.

#include <iostream>
#include <nlohmann/json.hpp>
#include <optional>

#include "commands.hpp"
#include "common_options.hpp"
#include "scanloc/io/candidate_report.hpp"
#include "scanloc/io/candidates_file.hpp"
#include "scanloc/io/scan_file.hpp"
#include "scanloc/session/localisation.hpp"

namespace scanloc::app {

void RegisterRefineCommand(CLI::App& app) {
  struct Arguments {
    MapArguments map;
    ConfigArguments config;
    std::string scan_path, candidates_path;
    std::optional<std::string> method, incidence;  // override refinement.method, ….incidence
    std::size_t scan_index = 0;
    bool json = false;
  };
  auto a = std::make_shared<Arguments>();
  CLI::App* command =
      app.add_subcommand("refine", "refine candidate postures and validate the results");
  a->map.Register(*command);
  a->config.Register(*command);
  command->add_option("--scan", a->scan_path, "scan file, or CARMEN log (.clf[.gz])")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--scan-index", a->scan_index, "which scan of a CARMEN log (0-based)")
      ->check(NonNegativeInteger());
  command->add_option("--candidates", a->candidates_path, "'x y theta [label]' per line")
      ->required()
      ->check(CLI::ExistingFile);
  command
      ->add_option("--method", a->method,
                   "ceres, error-descent or icp (default: refinement.method, ceres)")
      ->check(CLI::IsMember({"ceres", "error-descent", "icp"}));
  command
      ->add_option("--incidence", a->incidence,
                   "Ceres residual weighting by incidence: none, cosine or gate (default: "
                   "refinement.ceres.incidence, cosine)")
      ->check(CLI::IsMember({"none", "cosine", "gate"}));
  command->add_flag("--json", a->json, "print JSON (with histograms) instead of a table");
  command->final_callback([a] {
    Config config = a->config.Build();
    if (a->method) config.refiner.method = ParseRefinementMethod(*a->method);
    if (a->incidence) config.refiner.ceres.incidence = ParseIncidenceWeighting(*a->incidence);
    const LoadedMaps maps = LoadMaps(a->map, config);
    const LaserScan scan = LoadScan(a->scan_path, a->scan_index, config.log);
    const auto candidates = ReadCandidatesFile(a->candidates_path);
    const LocalisationResult result =
        Localise(maps.View(), scan, candidates, config.mounting,
                 {config.scoring, config.validation, config.refiner}, RefinePolicy::kAll);
    const std::string method = ToString(config.refiner.method);
    if (a->json) {
      nlohmann::json out = RefinedToJson(result);
      out["method"] = method;
      out["config"] = ToJson(config);
      std::cout << out.dump(2) << '\n';
    } else {
      std::cout << "method: " << method << '\n';
      PrintRefinementTable(std::cout, result);
    }
  });
}

}  // namespace scanloc::app
