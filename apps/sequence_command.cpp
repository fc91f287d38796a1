#include "sequence_command.hpp"

#include <atomic>
#include <cmath>
#include <csignal>
#include <filesystem>
#include <iomanip>
#include <iostream>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>

#include "scanloc/common/output_folder.hpp"
#include "scanloc/io/run_folder.hpp"
#include "scanloc/io/session_run.hpp"
#include "scanloc/maps/point_map_io.hpp"

namespace scanloc::app {
namespace {

std::atomic<bool> g_interrupted{false};
extern "C" void OnInterrupt(int) {
  g_interrupted = true;
}

// The inputs as absolute paths, so that `scanloc report` finds them from anywhere.
nlohmann::json Inputs(const SequenceArguments& a) {
  auto absolute = [](const std::string& path) {
    return path.empty()
               ? nlohmann::json(nullptr)
               : nlohmann::json(std::filesystem::absolute(path).lexically_normal().string());
  };
  return {{"log", absolute(a.log_path)},
          {"line_map", absolute(a.line_map_path)},
          {"point_map", absolute(a.point_map_path)}};
}

void PrintWarnings(const nlohmann::json& summary) {
  const std::size_t disordered = summary["timestamps_not_increasing"].get<std::size_t>();
  if (disordered > 0)
    std::cerr
        << "warning: " << disordered
        << " scans have a timestamp that is not after the previous scan's (kept in log order)\n";
  const std::size_t zero = summary["timestamps_zero"].get<std::size_t>();
  if (zero > 0)
    std::cerr << "warning: " << zero
              << " scans have a zero timestamp (the trajectory keeps them in log order; matching "
                 "it by time is ambiguous)\n";
  const std::size_t late_offsets = summary["laser_offsets_ignored"].get<std::size_t>();
  if (late_offsets > 0)
    std::cerr << "warning: " << late_offsets
              << " PARAM robot_frontlaser_offset lines after the first scan were ignored (the "
                 "mounting stays the one in force at the first scan)\n";
  if (!summary["skipped_messages"].empty()) {
    std::cout << "skipped messages:";
    for (const auto& [type, count] : summary["skipped_messages"].items())
      std::cout << " " << type << " " << count.get<std::size_t>();
    std::cout << "\n";
  }
  const std::size_t without = summary["localised_without_odometry"].get<std::size_t>();
  const std::size_t searched = summary["motion_searches"].get<std::size_t>();
  const std::size_t from_scans = summary["odometry_from_scans"].get<std::size_t>();
  if (without > 0)
    std::cout << "odometry: none for " << without << " localised scans"
              << (from_scans > 0 ? "; " + std::to_string(from_scans) +
                                       " of them moved by their match on the scan before"
                                 : std::string())
              << (searched > 0 ? "; the map was searched for " + std::to_string(searched) +
                                     " of them around the last posture, over the motion seen "
                                     "lately"
                               : std::string())
              << "\n";
  const std::size_t frozen = summary["odometry_frozen_scans"].get<std::size_t>();
  if (frozen > 0)
    std::cerr << "warning: the log's odometry had not moved since the first scan while the scans "
                 "did: "
              << frozen
              << " scans were taken without it (are the log's odometry fields filled in?)\n";
  const std::size_t reversed = summary["odometry_reversed_increments"].get<std::size_t>();
  if (reversed > 0)
    std::cout << "odometry: " << reversed
              << " increments reversed (the log's pose moved forward while ODOM reported a "
                 "negative velocity; --raw-odometry keeps them)\n";
}

// A localisation on a saved map: when it confirmed its posture, or loudly that it never did.
void PrintLocalisation(const SessionCounts& c) {
  if (!c.localisation) return;
  if (c.first_confirmed)
    std::cout << "localise: posture confirmed at scan " << *c.first_confirmed << ", "
              << c.first_confirmed_timestamp_s - c.first_timestamp_s << " s into the log; "
              << c.ambiguous << " scans ambiguous (at most " << c.max_hypotheses << " hypotheses), "
              << c.unposed << " without a posture\n";
  else
    std::cerr << "warning: no posture was ever confirmed on the map (" << c.ambiguous
              << " scans ambiguous, at most " << c.max_hypotheses << " hypotheses, " << c.unposed
              << " scans without a posture): trajectory.tum holds unconfirmed "
              << "guesses only\n";
}

// The odometry's calibration the confirmed steps taught, one line; a warning when a scale is
// significant and was not applied.
void PrintOdometryCalibration(const nlohmann::json& summary) {
  if (!summary.contains("odometry_calibration")) return;
  const nlohmann::json& c = summary["odometry_calibration"];
  const bool applied = c["applied"].get<bool>();
  auto scale = [](const nlohmann::json& s) {
    std::ostringstream text;
    text << "× " << s["fitted"].get<double>() << " ± " << s["standard_error"].get<double>()
         << (s["significant"].get<bool>() ? "" : " (not significant)");
    return text.str();
  };
  std::cout << "odometry calibration: from " << c["samples"] << " confirmed steps, distance "
            << scale(c["distance"]) << ", turn " << scale(c["turn"])
            << (applied ? " (applied)" : "") << "\n";
  auto off = [](const nlohmann::json& s) {  // how far the odometry is off, per cent
    return 100.0 * (1.0 / s["fitted"].get<double>() - 1.0);
  };
  const bool distance = c["distance"]["significant"].get<bool>();
  const bool turn = c["turn"]["significant"].get<bool>();
  if (applied || !(distance || turn)) return;
  std::ostringstream text;
  text << std::showpos << std::fixed << std::setprecision(1);
  if (distance) text << " distances " << off(c["distance"]) << " %";
  if (distance && turn) text << " and";
  if (turn) text << " turns " << off(c["turn"]) << " %";
  std::cerr << "warning: the confirmed scans say the odometry reports" << text.str()
            << " off; --set session.odometry_calibration_apply=true scales it by what they "
               "say\n";
}

// What the closures taught of the odometry (loop_closure.odometry_edges), one line.
void PrintOdometryModel(const nlohmann::json& loop_closure) {
  if (!loop_closure.contains("odometry_model")) return;
  const nlohmann::json& m = loop_closure["odometry_model"];
  if (!m.contains("heading_rad2_per_m")) {
    std::cout << "odometry: not learned (no closure confirmed over a stretch with odometry)\n";
    return;
  }
  std::cout << "odometry: learned from " << m["closures"] << " closures, heading "
            << 1e3 * std::sqrt(m["heading_rad2_per_m"].get<double>()) << " mrad and position "
            << 1e2 * std::sqrt(m["position_m2_per_m"].get<double>())
            << " cm per √m, matched chain's covariance × " << m["matched_scale"].get<double>()
            << " (heading test " << m["heading_test_statistic"].get<double>() << ")"
            << "; " << m["edges_in_graph"] << " of its steps hold the graph\n";
}

void PrintOutcome(const SessionRun& run, const nlohmann::json& summary, const RunFolder& folder,
                  const OccupancyGrid* grid) {
  const SessionCounts& c = run.counts;
  std::cout << "run: " << c.iterations << " scans (" << c.localised << " localised, " << c.validated
            << " validated, " << c.flagged << " flagged, " << c.refused_corrections
            << " corrections refused, " << c.slide_refusals << " refused as a slide, "
            << c.disputed_turns << " turns disputed by closures, " << c.tighter_refinements
            << " tighter refinements kept), map " << summary["map_points"] << " points, "
            << c.wall_s << " s (" << summary["times_real_time"].get<double>()
            << "× real time), peak " << summary["peak_resident_mb"].get<double>() << " MB"
            << (c.interrupted ? ", interrupted" : "") << "\n";
  if (c.searches > 0 || c.lost_stretches > 0)
    std::cout << "lost " << c.lost_stretches << " times, " << c.searches << " wide searches, "
              << c.recoveries << " recoveries" << (c.was_lost ? ", lost at the end" : "") << "\n";
  PrintLocalisation(c);
  PrintWarnings(summary);
  if (grid)
    std::cout << "occupancy grid: " << grid->width << " × " << grid->height << " cells of "
              << grid->resolution_m << " m from " << run.grid->scans() << " scans\n";
  const bool closing = summary.contains("loop_closure");
  const bool corrected = closing && summary["loop_closure"]["nodes"].get<std::size_t>() > 0;
  if (closing) {
    const nlohmann::json& l = summary["loop_closure"];
    std::cout << "loop closure: " << l["nodes"] << " nodes, " << l["closures_tried"]
              << " closures tried, " << l["closures_accepted"] << " accepted, "
              << l["closures_kept"] << " edges kept by the graph, " << l["map_renders"]
              << " map renders\n";
    if (l.contains("final_match")) {
      const nlohmann::json& f = l["final_match"];
      std::cout << "final map matching: " << f["matched"] << " nodes matched on the whole map, "
                << f["joined"] << " joined the graph";
      if (f.contains("from_neighbours"))
        std::cout << " (" << f["from_neighbours"]
                  << " also matched from where their neighbours put them, " << f["took_neighbours"]
                  << " joined from there)";
      std::cout << ", nodes moved up to " << f["largest_shift_m"] << " m\n";
    }
    PrintOdometryModel(l);
  }
  PrintOdometryCalibration(summary);
  std::cout << "wrote " << folder.directory() << "/{iterations.jsonl,trajectory.tum,map.pcd,"
            << (grid ? "map.pgm,map.yaml," : "") << (closing ? "graph.g2o," : "")
            << (corrected ? "trajectory-online.tum," : "") << "summary.json}\n";
}

// One line when the log's own saturation code lowers the range limit below log.max_range_m.
void ReportNoReturn(const IterationSource& source, const CarmenOptions& carmen) {
  const std::optional<double> recognised_m = source.recognised_no_return_m();
  if (recognised_m && *recognised_m < carmen.max_range_m)
    std::cerr << "log: readings at or beyond " << *recognised_m
              << " m are no-return (the log's saturation code; log.max_range_m is "
              << carmen.max_range_m << ", log.no_return_m sets it by hand)\n";
}

// A run whose localised scans were mostly not confirmed is said loudly (its trajectory is mostly
// odometry or unconfirmed guesses); under --strict it is an error.
void WarnIfMostlyUnconfirmed(const SessionCounts& c, bool strict) {
  if (!MostlyUnconfirmed(c)) return;
  const std::string message =
      std::to_string(c.flagged) + " of " + std::to_string(c.localised) +
      " localised scans were not confirmed by the Likelihood Test: the trajectory is not "
      "trustworthy (see iterations.jsonl, scanloc report)";
  if (strict) throw std::runtime_error(message);
  std::cerr << "warning: " << message << "\n";
}

// What the run is started with, as run.json: a resumed run must be started with the same.
nlohmann::json Identity(const SequenceArguments& a, const Config& config) {
  return {{"command", a.subcommand},
          {"inputs", Inputs(a)},
          {"config", ToJson(config)},
          {"skip_scans", a.skip_scans},
          {"laser_offset_m",
           a.laser_offset_m ? nlohmann::json(*a.laser_offset_m) : nlohmann::json(nullptr)},
          {"raw_odometry", a.raw_odometry},
          {"scan_topic", a.bag.scan_topic},
          {"odom_topic", a.bag.odometry_topic}};
}

// The run folder: new (or overwritten with --force), or the interrupted run's, to resume.
std::unique_ptr<RunFolder> OpenRunFolder(const SequenceArguments& a) {
  if (!a.resume) return std::make_unique<RunFolder>(a.out_dir, a.force);
  if (a.force) throw std::runtime_error("--resume and --force exclude each other");
  return std::make_unique<RunFolder>(a.out_dir, RunFolderOpening::kResume);
}

}  // namespace

void SequenceArguments::Register(CLI::App& command, const std::string& point_map_help) {
  subcommand = command.get_name();
  command
      .add_option("--log", log_path, "CARMEN log, ROS 1 bag or native sequence (told by content)")
      ->required()
      ->check(CLI::ExistingFile);
  command.add_option("--line-map", line_map_path, "off-line line map")->check(CLI::ExistingFile);
  command.add_option("--point-map", point_map_path, point_map_help)->check(CLI::ExistingFile);
  command.add_option("--out", out_dir, "run folder to write (new or empty)")->required();
  command.add_flag("--force", force, "write into an --out folder that is not empty");
  command.add_option("--laser-offset", laser_offset_m,
                     "laser distance ahead of the robot base (m); overrides the log's PARAM");
  command.add_option("--scan-topic", bag.scan_topic, "ROS bag: LaserScan topic (default /scan)");
  command.add_option("--odom-topic", bag.odometry_topic,
                     "ROS bag: Odometry topic (default /odom; without it, /tf odom → base_link)");
  command.add_option("--skip-scans", skip_scans, "start after this many scans of the log");
  command.add_option("--max-scans", max_scans, "stop after this many scans (0: all)");
  command.add_flag("--quiet", quiet, "no progress line on stderr");
  command.add_flag("--strict", strict,
                   "exit non-zero when most localised scans were not confirmed (the run is "
                   "written all the same)");
  command.add_flag("--raw-odometry", raw_odometry,
                   "use a CARMEN log's odometry as logged, without reversing the increments that "
                   "move forward while ODOM reports a negative velocity");
  config.Register(command);
}

void RunSequence(const SequenceArguments& a, Config config, const ProcessorMaker& make) {
  // Before anything is read (RunFolder checks again).
  if (!a.resume) RefuseNonEmptyFolder(a.out_dir, a.force);
  CarmenOptions carmen = config.log;  // --laser-offset and --raw-odometry override it
  if (a.laser_offset_m) carmen.laser_offset_m = a.laser_offset_m;
  if (a.raw_odometry) carmen.repair_reversed_odometry = false;
  RosBagOptions bag = a.bag;
  if (a.laser_offset_m) bag.mounting = Pose2D(*a.laser_offset_m, 0.0, 0.0);
  auto source = OpenIterationSource(a.log_path, carmen, bag);
  ReportNoReturn(*source, carmen);
  LineMap lines = a.line_map_path.empty() ? LineMap{} : ReadLineMap(a.line_map_path);
  PointMap points = a.point_map_path.empty() ? PointMap(config.point_map)
                                             : LoadPointMapPcd(a.point_map_path, config.point_map);
  const std::unique_ptr<RunFolder> opened = OpenRunFolder(a);
  RunFolder& folder = *opened;
  folder.Begin(Identity(a, config));
  std::signal(SIGINT, OnInterrupt);
  std::signal(SIGTERM, OnInterrupt);
  const SessionFactory make_session = [&](const IterationSource& from) {
    config.mounting =
        ChooseMounting(from.mounting(), config.mounting, carmen.laser_offset_m.has_value());
    return make(config, std::move(lines), std::move(points));
  };
  SessionRunOptions run_options;
  run_options.skip_scans = a.skip_scans;
  run_options.max_scans = a.max_scans;
  run_options.progress = !a.quiet;
  run_options.stop = &g_interrupted;
  if (config.write_occupancy_grid) run_options.occupancy_grid = config.occupancy_grid;
  if (!folder.recorded().empty())
    std::cerr << "resume: replaying " << folder.recorded().size() << " recorded iterations\n";
  const SessionRun run = RunSession(*source, make_session, folder, run_options);
  nlohmann::json summary = SummaryJson(run, *source);
  summary["log"] = a.log_path;
  summary["config"] = ToJson(config);
  summary["odometry_reversal_repair"] = carmen.repair_reversed_odometry;
  summary["inputs"] = Inputs(a);
  const PointMap empty_map(config.point_map);
  std::optional<OccupancyGrid> grid;
  if (run.grid && run.grid->scans() > 0) grid = run.grid->Build();
  try {
    if (run.session) {
      folder.Correct(run.session->CorrectedPostures());
      if (run.session->pose_graph()) folder.WriteGraph(*run.session->pose_graph());
    }
    folder.Finish(run.session ? run.session->point_map() : empty_map, summary,
                  grid ? &*grid : nullptr);
  } catch (const std::exception& e) {
    // A full disk fails the records first, then the files: both are said, the cause first.
    if (run.counts.failure.empty()) throw;
    throw std::runtime_error("the run stopped at scan " + std::to_string(run.counts.iterations) +
                             ": " + run.counts.failure + "; then " + e.what());
  }
  PrintOutcome(run, summary, folder, grid ? &*grid : nullptr);
  if (run.counts.failure.empty()) WarnIfMostlyUnconfirmed(run.counts, a.strict);
  if (!run.counts.failure.empty())
    throw std::runtime_error("the run stopped at scan " + std::to_string(run.counts.iterations) +
                             ": " + run.counts.failure + " (what it did before is written in " +
                             folder.directory() + ")");
}

}  // namespace scanloc::app
