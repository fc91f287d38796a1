// scanloc localise: localise every scan of a recorded sequence on a saved map that is never
// changed, from a given posture or from none (a global search), holding every hypothesis the
// Likelihood Test cannot yet tell apart.

#include <filesystem>
#include <iostream>
#include <memory>
#include <stdexcept>

#include "commands.hpp"
#include "scanloc/io/run_summary.hpp"
#include "scanloc/session/localiser.hpp"
#include "sequence_command.hpp"

namespace scanloc::app {
namespace {

// Rule 2's prior E_max becomes the point map's own signature when the session that wrote the map
// left one beside it: the finished map fits its own scans more loosely than the laser alone. Its
// sampled scans raise the bound where the map fits worse than its median (place_bound.hpp).
void UseMapSignature(const SequenceArguments& a, Config& config, LocaliserConfig& localiser) {
  if (a.point_map_path.empty() || !config.localise.map_signature) return;
  const auto summary = std::filesystem::path(a.point_map_path).parent_path() / "summary.json";
  const std::optional<MapSignature> signature = ReadMapSignature(summary.string());
  if (!signature) {
    if (!a.quiet)
      std::cerr << "localise: no map signature in " << summary.string()
                << ": rule 2's prior E_max is " << config.validation.max_expect_value_m
                << " m until the posture's own signature learns\n";
    return;
  }
  if (!a.quiet)
    std::cerr << "localise: rule 2's prior E_max " << signature->max_expect_value_m
              << " m, the map's own signature (" << summary.string()
              << "; --set localise.map_signature=false for "
              << config.validation.max_expect_value_m << " m)\n";
  config.validation.max_expect_value_m = signature->max_expect_value_m;
  if (!config.localise.place_bound) return;
  if (signature->samples.empty()) {
    if (!a.quiet)
      std::cerr << "localise: the map signature holds no sampled scans (a map written before "
                   "they were kept): the bound is the same at every place\n";
    return;
  }
  if (!a.quiet)
    std::cerr << "localise: rule 2's bound raised where the map's " << signature->samples.size()
              << " sampled scans fit worse than its median EV "
              << signature->median_expect_value_m
              << " m (--set localise.place_bound=false: the same everywhere)\n";
  localiser.place_bound = PlaceBound(signature->samples, signature->median_expect_value_m);
}

void Run(const SequenceArguments& a) {
  if (a.point_map_path.empty() && a.line_map_path.empty())
    throw std::invalid_argument(
        "localise needs a map: --point-map MAP.pcd, --line-map FILE, or both");
  Config config = a.config.Build();
  LocaliserConfig localiser;
  UseMapSignature(a, config, localiser);
  config.write_occupancy_grid = false;  // the map is not the run's: it is not rebuilt
  localiser.localiser = config.localise;
  if (!a.initial_pose.empty())
    localiser.initial_pose = Pose2D(a.initial_pose[0], a.initial_pose[1], a.initial_pose[2]);
  RunSequence(a, config, [&](const Config& c, LineMap lines, PointMap points) {
    localiser.session = c.session;
    localiser.localisation = {c.scoring, c.validation, c.refiner};
    return std::make_unique<Localiser>(localiser, c.mounting, std::move(lines), std::move(points));
  });
}

}  // namespace

void RegisterLocaliseCommand(CLI::App& app) {
  auto arguments = std::make_shared<SequenceArguments>();
  CLI::App* command = app.add_subcommand(
      "localise",
      "localise a recorded sequence on a saved map (never changed), from an unknown start");
  arguments->Register(*command, "saved point map (PCD) to localise on");
  command
      ->add_option("--initial-pose", arguments->initial_pose,
                   "the first posture x y theta when known (default: searched on the map)")
      ->expected(3)
      ->check(PlausibleCoordinate());
  command->final_callback([arguments] { Run(*arguments); });
}

}  // namespace scanloc::app
