// scanloc session: localise every scan of a recorded sequence against the map built so far, extend
// the map, and write the run folder.

#include <memory>

#include "commands.hpp"
#include "scanloc/session/session.hpp"
#include "sequence_command.hpp"

namespace scanloc::app {
namespace {

void Run(const SequenceArguments& a) {
  Config config = a.config.Build();
  if (!a.initial_pose.empty()) {
    config.session.initial_pose = {a.initial_pose[0], a.initial_pose[1], a.initial_pose[2]};
    config.Validate();  // the ranges of the config, e.g. |yaw| ≤ 2π
  }
  RunSequence(a, config, [](const Config& c, LineMap lines, PointMap points) {
    return std::make_unique<Session>(SessionConfig{c.session, {c.scoring, c.validation, c.refiner}},
                                     c.mounting, std::move(lines), std::move(points));
  });
}

}  // namespace

void RegisterSessionCommand(CLI::App& app) {
  auto arguments = std::make_shared<SequenceArguments>();
  CLI::App* command = app.add_subcommand(
      "session", "localise a whole recorded sequence while growing the map from its scans");
  arguments->Register(*command, "saved point map (PCD) to start from");
  command
      ->add_option("--initial-pose", arguments->initial_pose,
                   "first posture x y theta (default 0 0 0)")
      ->expected(3)
      ->check(PlausibleCoordinate());
  command->add_flag("--resume", arguments->resume,
                    "continue the interrupted or killed run in --out from its iterations.jsonl "
                    "(same inputs and options; ends with the files an uninterrupted run writes)");
  command->final_callback([arguments] { Run(*arguments); });
}

}  // namespace scanloc::app
