// scanloc: incremental 2D laser localisation and mapping with the Likelihood Test.

#include <CLI/CLI.hpp>
#include <exception>
#include <iostream>

#include "commands.hpp"
#include "scanloc/common/parallel_for.hpp"

int main(int argc, char** argv) {
  CLI::App app{"scanloc: 2D laser localisation and mapping with the Likelihood Test"};
  app.require_subcommand(1);
  app.fallthrough();  // --threads may follow the subcommand's name
  app.add_option("--threads",
                 "threads for the parallel loops, the caller's included (default 1: "
                 "everything on the calling thread; 0: one per hardware thread)")
      ->check(CLI::Range(0, 1024))
      ->each([](const std::string& value) { scanloc::SetParallelThreads(std::stoul(value)); });
  scanloc::app::RegisterTestCommand(app);
  scanloc::app::RegisterSimulateScanCommand(app);
  scanloc::app::RegisterRefineCommand(app);
  scanloc::app::RegisterSessionCommand(app);
  scanloc::app::RegisterLocaliseCommand(app);
  scanloc::app::RegisterEvaluateCommand(app);
  scanloc::app::RegisterReportCommand(app);
  scanloc::app::RegisterSimulateCommand(app);
  scanloc::app::RegisterCompareCommand(app);
  scanloc::app::RegisterOptionsCommand(app);
  scanloc::app::RegisterExportGridCommand(app);
  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    return app.exit(e);
  } catch (const std::exception& e) {
    std::cerr << "scanloc: error: " << e.what() << '\n';
    return 1;
  }
  return 0;
}
