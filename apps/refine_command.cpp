// scanloc refine: every candidate before and after refinement, as the chapter's Tables 2, 5, 6, 8.

#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "common_options.hpp"
#include "scanloc/io/candidate_report.hpp"
#include "scanloc/io/candidates_file.hpp"
#include "scanloc/io/scan_file.hpp"
#include "scanloc/session/candidate_refinement.hpp"

namespace scanloc::app {

void RegisterRefineCommand(CLI::App& app) {
  struct Arguments {
    MapArguments map;
    ConfigArguments config;
    std::string scan_path, candidates_path, method = "ceres", incidence = "cosine";
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
  command->add_option("--method", a->method, "ceres, error-descent or icp")
      ->check(CLI::IsMember({"ceres", "error-descent", "icp"}));
  command
      ->add_option("--incidence", a->incidence,
                   "Ceres residual weighting by incidence: none, cosine or gate")
      ->check(CLI::IsMember({"none", "cosine", "gate"}));
  command->add_flag("--json", a->json, "print JSON (with histograms) instead of a table");
  command->final_callback([a] {
    const Config config = a->config.Build();
    const LoadedMaps maps = LoadMaps(a->map, config);
    const LaserScan scan = LoadScan(a->scan_path, a->scan_index);
    const auto candidates = ReadCandidatesFile(a->candidates_path);
    RefinerOptions refiner;
    refiner.method = ParseRefinementMethod(a->method);
    refiner.ceres.incidence = ParseIncidenceWeighting(a->incidence);
    refiner.error_descent.alpha_m = config.validation.alpha_m;
    const auto result = RefineCandidates(maps.View(), scan, candidates, config.mounting,
                                         config.scoring, config.validation, refiner);
    if (a->json) {
      nlohmann::json out = ToJson(result);
      out["method"] = a->method;
      std::cout << out.dump(2) << '\n';
    } else {
      std::cout << "method: " << a->method << '\n';
      PrintRefinementTable(std::cout, result);
    }
  });
}

}  // namespace scanloc::app
