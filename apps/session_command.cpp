// scanloc session: localise every scan of a recorded sequence against the map built so far, extend
// the map, and write the run folder.

#include <sys/resource.h>

#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "common_options.hpp"
#include "scanloc/io/run_folder.hpp"
#include "scanloc/io/sequence_sources.hpp"
#include "scanloc/maps/point_map_io.hpp"

namespace scanloc::app {
namespace {

std::atomic<bool> g_interrupted{false};
extern "C" void OnInterrupt(int) {
  g_interrupted = true;
}

double PeakResidentMegabytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return usage.ru_maxrss / 1024.0;  // Linux reports kilobytes
}

std::size_t ReversedIncrementsOf(const IterationSource& source) {
  const auto* carmen = dynamic_cast<const CarmenIterationSource*>(&source);
  return carmen != nullptr ? carmen->reversed_increments() : 0;
}

double ProgressOf(const IterationSource& source) {
  if (const auto* carmen = dynamic_cast<const CarmenIterationSource*>(&source))
    return carmen->Progress();
  if (const auto* native = dynamic_cast<const SequenceFileSource*>(&source))
    return native->Progress();
  return 0.0;
}

}  // namespace

void RegisterSessionCommand(CLI::App& app) {
  struct Arguments {
    std::string log_path, line_map_path, point_map_path, out_dir;
    ConfigArguments config;
    std::vector<double> initial_pose;
    std::optional<double> laser_offset_m;
    std::size_t max_scans = 0;
    bool quiet = false;
    bool raw_odometry = false;
  };
  auto a = std::make_shared<Arguments>();
  CLI::App* command = app.add_subcommand(
      "session", "localise a whole recorded sequence while growing the map from its scans");
  command->add_option("--log", a->log_path, "CARMEN log (.clf[.gz]) or native sequence (.jsonl)")
      ->required()
      ->check(CLI::ExistingFile);
  command->add_option("--line-map", a->line_map_path, "off-line line map")
      ->check(CLI::ExistingFile);
  command->add_option("--point-map", a->point_map_path, "saved point map (PCD) to start from")
      ->check(CLI::ExistingFile);
  command->add_option("--out", a->out_dir, "run folder to write")->required();
  command->add_option("--initial-pose", a->initial_pose, "first posture x y theta (default 0 0 0)")
      ->expected(3)
      ->check(PlausibleCoordinate());
  command->add_option("--laser-offset", a->laser_offset_m,
                      "laser distance ahead of the robot base (m); overrides the log's PARAM");
  command->add_option("--max-scans", a->max_scans, "stop after this many scans (0: all)");
  command->add_flag("--quiet", a->quiet, "no progress line on stderr");
  command->add_flag("--raw-odometry", a->raw_odometry,
                    "use a CARMEN log's odometry as logged, without reversing the increments that "
                    "move forward while ODOM reports a negative velocity");
  a->config.Register(*command);
  command->final_callback([a] {
    Config config = a->config.Build();
    if (!a->initial_pose.empty()) {
      config.session.initial_pose = {a->initial_pose[0], a->initial_pose[1], a->initial_pose[2]};
      config.session.Validate();
    }
    CarmenOptions carmen;
    carmen.laser_offset_m = a->laser_offset_m;
    carmen.repair_reversed_odometry = !a->raw_odometry;
    auto source = OpenIterationSource(a->log_path, carmen);
    LineMap lines = a->line_map_path.empty() ? LineMap{} : ReadLineMap(a->line_map_path);
    PointMap points = a->point_map_path.empty()
                          ? PointMap(config.point_map)
                          : LoadPointMapPcd(a->point_map_path, config.point_map);
    RunFolder run(a->out_dir);

    std::signal(SIGINT, OnInterrupt);
    std::signal(SIGTERM, OnInterrupt);
    const auto start = std::chrono::steady_clock::now();
    auto last_progress = start;
    std::unique_ptr<Session> session;
    std::size_t localised = 0, skipped = 0, validated = 0, flagged = 0, inserted = 0;
    double first_t = 0.0, min_t = 0.0, max_t = 0.0;
    Iteration iteration;
    auto wanted = [&] {
      return a->max_scans == 0 || !session || session->iterations() < a->max_scans;
    };
    while (!g_interrupted && wanted() && source->Next(iteration)) {
      if (!session) {
        // The mounting is final once the first scan was read (CARMEN's PARAM precedes it):
        // --laser-offset, else the config's when it sets one, else the log's.
        const Pose2D& configured = config.mounting.T_robot_laser;
        const bool config_sets_mounting =
            configured.x_m != 0.0 || configured.y_m != 0.0 || configured.yaw_rad != 0.0;
        const LaserMounting mounting =
            a->laser_offset_m || !config_sets_mounting ? source->mounting() : config.mounting;
        config.mounting = mounting;
        session = std::make_unique<Session>(config.session, config.scoring, config.validation,
                                            config.refiner, mounting, std::move(lines),
                                            std::move(points));
        first_t = min_t = max_t = iteration.timestamp_s;
      }
      const IterationRecord record = session->Process(iteration);
      run.Record(record);
      min_t = std::min(min_t, record.timestamp_s);
      max_t = std::max(max_t, record.timestamp_s);
      skipped += record.skipped;
      localised += !record.skipped;
      validated += record.validated;
      flagged += !record.skipped && !record.validated;
      inserted += record.inserted;
      const auto now = std::chrono::steady_clock::now();
      if (!a->quiet && now - last_progress > std::chrono::seconds(2)) {
        last_progress = now;
        const double elapsed = std::chrono::duration<double>(now - start).count();
        const double progress = ProgressOf(*source);
        const double eta = progress > 0.0 ? elapsed * (1.0 - progress) / progress : 0.0;
        std::fprintf(
            stderr,
            "\rscans %zu, %.0f scans/s, %.0f× real time, map %zu points, %3.0f %%, ETA %.0f s   ",
            session->iterations(), session->iterations() / elapsed, (max_t - min_t) / elapsed,
            record.map_points, 100.0 * progress, eta);
      }
    }
    if (!a->quiet) std::fprintf(stderr, "\n");
    const double wall_s =
        std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    const std::size_t count = session ? session->iterations() : 0;
    nlohmann::json summary = {{"log", a->log_path},
                              {"interrupted", g_interrupted.load()},
                              {"iterations", count},
                              {"localised", localised},
                              {"skipped", skipped},
                              {"validated", validated},
                              {"flagged_not_validated", flagged},
                              {"inserted", inserted},
                              {"map_points", session ? session->point_map().live_size() : 0},
                              {"wall_time_s", wall_s},
                              {"data_span_s", max_t - min_t},
                              {"first_timestamp_s", first_t},
                              {"scans_per_s", wall_s > 0 ? count / wall_s : 0.0},
                              {"times_real_time", wall_s > 0 ? (max_t - min_t) / wall_s : 0.0},
                              {"peak_resident_mb", PeakResidentMegabytes()},
                              {"config", ToJson(config)}};
    if (count == 0) summary["problem"] = "the sequence has no scan";
    const std::size_t reversed = ReversedIncrementsOf(*source);
    summary["odometry_reversal_repair"] = carmen.repair_reversed_odometry;
    summary["odometry_reversed_increments"] = reversed;
    // The inputs as absolute paths, so that `scanloc report` finds them from anywhere (the mounting
    // in force is config.mounting).
    auto absolute = [](const std::string& path) {
      return path.empty()
                 ? nlohmann::json(nullptr)
                 : nlohmann::json(std::filesystem::absolute(path).lexically_normal().string());
    };
    summary["inputs"] = {{"log", absolute(a->log_path)},
                         {"line_map", absolute(a->line_map_path)},
                         {"point_map", absolute(a->point_map_path)}};
    const PointMap empty_map(config.point_map);
    run.Finish(session ? session->point_map() : empty_map, summary);
    std::cout << "session: " << count << " scans (" << localised << " localised, " << validated
              << " validated, " << flagged << " flagged), map " << summary["map_points"]
              << " points, " << wall_s << " s (" << summary["times_real_time"].get<double>()
              << "× real time), peak " << summary["peak_resident_mb"].get<double>() << " MB"
              << (g_interrupted ? ", interrupted" : "") << "\n";
    if (reversed > 0)
      std::cout << "odometry: " << reversed
                << " increments reversed (the log's pose moved forward while ODOM reported a "
                   "negative velocity; --raw-odometry keeps them)\n";
    std::cout << "wrote " << run.directory()
              << "/{iterations.jsonl,trajectory.tum,map.pcd,summary.json}\n";
  });
}

}  // namespace scanloc::app
