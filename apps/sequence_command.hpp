#pragma once
// What `scanloc session` and `scanloc localise` share: the arguments that name a recorded
// sequence, its maps and the run folder; the run over the sequence into that folder; and what is
// said to the operator at the end.

#include <CLI/CLI.hpp>
#include <functional>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "common_options.hpp"
#include "scanloc/io/sequence_sources.hpp"
#include "scanloc/maps/line_map.hpp"
#include "scanloc/maps/point_map.hpp"
#include "scanloc/session/scan_processor.hpp"

namespace scanloc::app {

struct SequenceArguments {
  std::string log_path, line_map_path, point_map_path, out_dir;
  ConfigArguments config;
  std::vector<double> initial_pose;
  std::optional<double> laser_offset_m;
  std::size_t skip_scans = 0;
  std::size_t max_scans = 0;
  bool quiet = false;
  bool strict = false;
  bool raw_odometry = false;
  bool force = false;
  bool resume = false;  // `scanloc session --resume` only
  std::string subcommand;  // the subcommand's name, for run.json
  RosBagOptions bag;

  // `point_map_help` says what the saved point map is to the command.
  void Register(CLI::App& command, const std::string& point_map_help);
};

// Makes what processes the scans, once the first scan is read and the mounting is final.
using ProcessorMaker = std::function<std::unique_ptr<ScanProcessor>(
    const Config& config, LineMap lines, PointMap points)>;

// Reads the inputs, runs `make`'s processor over the sequence into the run folder, writes it and
// tells the operator; throws when the run failed (what it did is written all the same) or, under
// --strict, when most localised scans were not confirmed. `config` comes from the arguments.
// With `resume`, the run folder's records are replayed first and the run goes on after them.
void RunSequence(const SequenceArguments& arguments, Config config, const ProcessorMaker& make);

}  // namespace scanloc::app
