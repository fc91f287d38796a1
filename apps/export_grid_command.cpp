// scanloc export-grid: an occupancy grid (map_server's map.pgm + map.yaml) from a session's run
// folder, casting the logged scans at the postures the session kept.

#include <filesystem>
#include <iostream>

#include "commands.hpp"
#include "scanloc/common/output_folder.hpp"
#include "scanloc/io/run_grid.hpp"

namespace scanloc::app {
namespace {

struct ExportGridArguments {
  RunGridRequest request;
  std::string out_dir, name = "map";
  bool force = false;
};

void ExportGrid(const ExportGridArguments& a) {
  const std::string out = a.out_dir.empty() ? a.request.run_dir : a.out_dir;
  const OccupancyGridFiles target = OccupancyGridPaths(out, a.name);
  RefuseToReplace({target.image_path, target.yaml_path}, a.force);
  const RunGrid grid = BuildRunFolderGrid(a.request);
  if (grid.simulated_from_map)
    std::cout << "export-grid: no log: scans simulated from map.pcd at the session's postures\n";
  std::filesystem::create_directories(out);
  const OccupancyGridFiles files = WriteOccupancyGrid(out, grid.built.grid, a.name);
  std::cout << "export-grid: " << grid.built.scans_used << " of " << grid.built.scans_read
            << " scans, " << grid.built.grid.width << " × " << grid.built.grid.height
            << " cells of " << grid.built.grid.resolution_m << " m\nwrote " << files.image_path
            << ", " << files.yaml_path << "\n";
}

}  // namespace

void RegisterExportGridCommand(CLI::App& app) {
  auto a = std::make_shared<ExportGridArguments>();
  CLI::App* command = app.add_subcommand(
      "export-grid",
      "occupancy grid (map_server's map.pgm + map.yaml) from a session's run folder");
  command->add_option("RUN_DIR", a->request.run_dir, "run folder of `scanloc session`")
      ->required()
      ->check(CLI::ExistingDirectory);
  command
      ->add_option("--log", a->request.log_path,
                   "the session's log (default: summary.json's inputs.log)")
      ->check(CLI::ExistingFile);
  command->add_option("--resolution", a->request.options.resolution_m, "cell side in metres")
      ->check(CLI::PositiveNumber);
  command->add_option("--out", a->out_dir,
                      "folder to write map.pgm and map.yaml (default RUN_DIR)");
  command->add_option("--name", a->name, "file name without extension");
  command->add_flag("--all-scans", a->request.all_scans,
                    "cast every localised scan, not only the validated ones");
  command->add_flag("--force", a->force,
                    "replace an existing <name>.pgm / <name>.yaml (a session writes map.*)");
  command->final_callback([a] { ExportGrid(*a); });
}

}  // namespace scanloc::app
