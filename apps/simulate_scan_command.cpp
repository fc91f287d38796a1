// scanloc simulate-scan: one laser scan of a line world from a known posture, with noise.

#include <cmath>
#include <iostream>
#include <random>

#include "commands.hpp"
#include "scanloc/io/scan_file.hpp"
#include "scanloc/worlds/laser_simulator.hpp"

namespace scanloc::app {

void RegisterSimulateScanCommand(CLI::App& app) {
  struct Arguments {
    std::vector<std::string> world_paths;
    std::vector<double> pose{0.0, 0.0, 0.0};
    std::string out_path;
    unsigned seed = 1;
    LaserSimulatorOptions laser;
    std::vector<double> body_sector;
  };
  auto a = std::make_shared<Arguments>();
  CLI::App* command = app.add_subcommand(
      "simulate-scan", "simulate one laser scan of a line world (map plus clutter) at a posture");
  command->add_option("--world", a->world_paths, "line files that make the world (map, clutter)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--pose", a->pose, "laser posture x y theta (m, m, rad)")
      ->expected(3)
      ->required();
  command->add_option("--out", a->out_path, "scan file to write")->required();
  command->add_option("--seed", a->seed, "random seed");
  command->add_option("--beams", a->laser.beam_count, "points per revolution");
  command->add_option("--fov", a->laser.fov_rad, "field of view (rad)");
  command->add_option("--range-max", a->laser.range_max_m, "maximum range (m)");
  command->add_option("--reliable-range", a->laser.reliable_range_m, "reliable range (m)");
  command->add_option("--noise", a->laser.range_noise_m, "range noise σ at short range (m)");
  command->add_option("--noise-per-m", a->laser.range_noise_per_m, "σ growth per metre");
  command->add_option("--dropout", a->laser.dropout_probability, "missing-return probability");
  command
      ->add_option("--body-sector", a->body_sector,
                   "bearings (rad, laser frame) hitting the robot body: FROM TO")
      ->expected(2);
  command->final_callback([a] {
    for (const double v : a->pose)
      if (!std::isfinite(v)) throw std::runtime_error("--pose: expected three finite numbers");
    if (!a->body_sector.empty()) {
      a->laser.body_from_rad = a->body_sector[0];
      a->laser.body_to_rad = a->body_sector[1];
    }
    LineMap world;
    for (const auto& path : a->world_paths) {
      const LineMap part = ReadLineMap(path);
      world.segments.insert(world.segments.end(), part.segments.begin(), part.segments.end());
    }
    std::mt19937 rng(a->seed);
    const Pose2D pose{a->pose[0], a->pose[1], a->pose[2]};
    const LaserScan scan = SimulateLaser(world, pose, a->laser, rng);
    WriteScanFile(scan, a->out_path);
    std::cout << "wrote " << a->out_path << ": " << scan.size() << " beams, " << scan.CountValid()
              << " valid\n";
  });
}

}  // namespace scanloc::app
