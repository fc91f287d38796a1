// scanloc simulate: one of the chapter's environments as files (line map, world, sequence with
// ground truth), the same bytes for the same seed.

#include <iostream>

#include "commands.hpp"
#include "scanloc/common/output_folder.hpp"
#include "scanloc/io/environment_files.hpp"

namespace scanloc::app {

void RegisterSimulateCommand(CLI::App& app) {
  struct Arguments {
    std::string environment, out_dir;
    unsigned seed = 1;
    std::size_t iterations = 0;
    bool force = false;
  };
  auto a = std::make_shared<Arguments>();
  CLI::App* command = app.add_subcommand(
      "simulate",
      "simulate one of the chapter's environments: line map, world and a sequence of scans along "
      "a robot path with odometry and ground truth");
  command->add_option("--environment", a->environment, "classroom, office or factory")
      ->required()
      ->check(CLI::IsMember(EnvironmentNames()));
  command->add_option("--seed", a->seed, "random seed (odometry, range noise, missing returns)")
      ->capture_default_str();
  command->add_option("--out", a->out_dir, "directory to write the files into (new or empty)")
      ->required();
  command->add_flag("--force", a->force, "write into an --out folder that is not empty");
  command->add_option("--iterations", a->iterations,
                      "stop the path after this many iterations (0: the whole path)");
  command->final_callback([a] {
    RefuseNonEmptyFolder(a->out_dir, a->force);
    const EnvironmentFiles files =
        WriteEnvironmentFiles(MakeEnvironment(a->environment), a->seed, a->out_dir, a->iterations);
    std::cout << "simulated " << a->environment << " (seed " << a->seed << "): " << files.iterations
              << " iterations\n";
    for (const auto& path : files.paths) std::cout << "wrote " << path << '\n';
  });
}

}  // namespace scanloc::app
