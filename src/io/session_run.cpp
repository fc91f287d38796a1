#include "scanloc/io/session_run.hpp"

#include <sys/resource.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <nlohmann/json.hpp>

#include "scanloc/io/run_grid.hpp"

namespace scanloc {
namespace {

using Clock = std::chrono::steady_clock;

double SecondsSince(Clock::time_point start) {
  return std::chrono::duration<double>(Clock::now() - start).count();
}

double PeakResidentMegabytes() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  return static_cast<double>(usage.ru_maxrss) / 1024.0;  // Linux reports kilobytes
}

// User + system CPU seconds of the whole process, every thread's.
double ProcessCpuSeconds() {
  rusage usage{};
  getrusage(RUSAGE_SELF, &usage);
  const auto seconds = [](const timeval& t) { return t.tv_sec + 1e-6 * t.tv_usec; };
  return seconds(usage.ru_utime) + seconds(usage.ru_stime);
}

void PrintProgress(const SessionRun& run, const IterationSource& source, double elapsed_s,
                   std::size_t map_points) {
  const double progress = source.Progress();
  const double eta_s = progress > 0.0 ? elapsed_s * (1.0 - progress) / progress : 0.0;
  const SessionCounts& c = run.counts;
  std::fprintf(
      stderr,
      "\rscans %zu (%zu confirmed, %zu not, lost %zu×%s), %.0f× real time, map %zu points, "
      "%3.0f %%, ETA %.0f s   ",
      c.iterations, c.validated, c.flagged, c.lost_stretches, c.was_lost ? " now" : "",
      c.span_s() / elapsed_s, map_points, 100.0 * progress, eta_s);
}

nlohmann::json Nullable(const std::optional<double>& value) {
  return value ? nlohmann::json(*value) : nlohmann::json(nullptr);
}

// What a localisation on a saved map adds: when it first confirmed its posture, how long the
// scans were ambiguous, and said loudly when it never confirmed one.
void AddLocalisationSummary(const SessionCounts& c, nlohmann::json& summary) {
  summary["first_confirmed_scan"] =
      c.first_confirmed ? nlohmann::json(*c.first_confirmed) : nlohmann::json(nullptr);
  summary["seconds_to_confirm"] =
      c.first_confirmed ? nlohmann::json(c.first_confirmed_timestamp_s - c.first_timestamp_s)
                        : nlohmann::json(nullptr);
  summary["ambiguous_scans"] = c.ambiguous;
  summary["max_hypotheses"] = c.max_hypotheses;
  summary["scans_without_posture"] = c.unposed;
  nlohmann::json series = nlohmann::json::array();
  for (const SessionCounts::HypothesesPoint& p : c.hypotheses_over_time) {
    series.push_back({{"scan", p.scan},
                      {"timestamp_s", p.timestamp_s},
                      {"state", p.state},
                      {"hypotheses", p.hypotheses}});
    if (!p.discarded.empty()) series.back()["discarded"] = p.discarded;
  }
  summary["hypotheses_over_time"] = series;
  if (!c.first_confirmed) summary["problem"] = "no posture was ever confirmed on the map";
}

// Closure edges the graph still holds active after its last solve.
// The map signature's sampled scans, [x_m, y_m, expect_value_m] each: the per-place bound's
// evidence (`scanloc localise`, session/place_bound.hpp).
nlohmann::json SignatureSamples(const MapSignature& signature) {
  nlohmann::json samples = nlohmann::json::array();
  for (const MapSignatureSample& s : signature.samples)
    samples.push_back({s.x_m, s.y_m, s.expect_value_m});
  return samples;
}

// What the closures taught of the odometry: how many, the scales fitted to their misses (none
// before the first), and how many odometry edges hold the graph.
nlohmann::json OdometryModelSummary(const OdometryModel& model, const PoseGraph& graph) {
  std::size_t edges = 0;
  for (const PoseGraphEdge& edge : graph.edges())
    edges += edge.kind == EdgeKind::kOdometry && edge.active;
  nlohmann::json json = {{"closures", model.closures()}, {"edges_in_graph", edges}};
  if (!model.learned()) return json;
  json["position_m2_per_m"] = model.position_m2_per_m();
  json["heading_rad2_per_m"] = model.heading_rad2_per_m();
  json["matched_scale"] = model.matched_scale();
  json["heading_test_statistic"] = model.heading_test_statistic();
  json["position_test_statistic"] =
      model.position_test_statistic() ? nlohmann::json(*model.position_test_statistic()) : nullptr;
  json["matching_heading_jitter_rad2"] = model.heading_jitter_rad2();
  return json;
}

// The odometry's calibration: whether it is applied, and each scale's value in use, last fit,
// standard error, samples and significance.
nlohmann::json OdometryCalibrationSummary(const OdometryCalibration& calibration) {
  auto scale = [](const OdometryScale& s) {
    return nlohmann::json{{"value", s.value},
                          {"fitted", s.fitted},
                          {"standard_error", s.standard_error},
                          {"samples", s.samples},
                          {"significant", s.significant}};
  };
  return {{"samples", calibration.samples()},
          {"applied", calibration.applies()},
          {"distance", scale(calibration.distance())},
          {"turn", scale(calibration.turn())}};
}

std::size_t ClosuresKept(const PoseGraph& graph) {
  std::size_t kept = 0;
  for (const PoseGraphEdge& edge : graph.edges())
    kept += edge.kind == EdgeKind::kClosure && edge.active;
  return kept;
}

}  // namespace

void SessionCounts::Add(const IterationRecord& record) {
  if (iterations == 0) first_timestamp_s = min_timestamp_s = max_timestamp_s = record.timestamp_s;
  ++iterations;
  min_timestamp_s = std::min(min_timestamp_s, record.timestamp_s);
  max_timestamp_s = std::max(max_timestamp_s, record.timestamp_s);
  skipped += record.skipped;
  localised += !record.skipped;
  validated += record.validated;
  flagged += !record.skipped && !record.validated;
  inserted += record.inserted;
  searches += record.search.has_value() && !record.motion_search;
  without_odometry += record.without_odometry;
  motion_searches += record.motion_search || record.motion_searched_hypotheses > 0;
  odometry_from_scans += record.odometry_from_scans;
  odometry_frozen += record.odometry_frozen;
  recoveries += record.recovered;
  refused_corrections += record.beyond_odometry;
  slide_refusals += record.slide_refused;
  new_ground += record.new_ground;
  disputed_turns += record.turn_dispute.has_value();
  tighter_refinements += record.outranked_refinement >= 0;
  lost_stretches += record.lost && !was_lost;
  was_lost = record.lost;
  localisation = localisation || !record.state.empty();
  if (!first_confirmed && record.state == "confirmed") {
    first_confirmed = iterations - 1;
    first_confirmed_timestamp_s = record.timestamp_s;
  }
  ambiguous += record.state == "ambiguous";
  if (!record.state.empty() &&
      (hypotheses_over_time.empty() || hypotheses_over_time.back().state != record.state ||
       hypotheses_over_time.back().hypotheses != record.hypotheses.size()))
    hypotheses_over_time.push_back({iterations - 1, record.timestamp_s, record.state,
                                    record.hypotheses.size(), record.discarded});
  max_hypotheses = std::max(max_hypotheses, record.hypotheses.size());
  unposed += !record.posed;
  if (record.closure) {
    ++closures_tried;
    closures_accepted += record.closure->accepted;
    map_renders += record.closure->rendered;
  }
}

bool MostlyUnconfirmed(const SessionCounts& counts) {
  return counts.localised > 0 && 2 * counts.flagged > counts.localised;
}

namespace {

// The next iteration processed into `run`: replayed while the run folder holds records to resume
// from (a mismatch is thrown with the record's line), processed and recorded after them.
IterationRecord ProcessOne(ScanProcessor& session, const Iteration& iteration, RunFolder& run,
                           std::size_t index) {
  if (index >= run.recorded().size()) {
    IterationRecord record = session.Process(iteration);
    run.Record(record);
    return record;
  }
  try {
    IterationRecord record = session.Replay(iteration, run.recorded()[index]);
    run.Replayed(record);
    return record;
  } catch (const std::exception& e) {
    throw ReplayMismatch(run.Path("iterations.jsonl") + ":" + std::to_string(index + 1) +
                         ": cannot resume: " + e.what() +
                         " (was the run made from another log or by another version of scanloc?)");
  }
}

// The grid's scans moved to the postures the session corrected after the run (loop closure), so
// that map.pgm shows the map trajectory.tum and map.pcd show; a scan without a corrected posture
// stays where the session kept it.
void MoveToCorrectedPostures(const ScanProcessor& session, const std::vector<std::size_t>& records,
                             OccupancyGridBuilder& grid) {
  const std::vector<std::optional<Pose2D>> corrected = session.CorrectedPostures();
  for (std::size_t k = 0; k < records.size(); ++k)
    if (records[k] < corrected.size() && corrected[records[k]])
      grid.MoveScan(k, session.mounting().LaserPose(*corrected[records[k]]));
}

// A resumed run that did not get past its records has nothing new to write: the folder stays as
// it was.
void RequireReplayDone(const SessionRun& result, const RunFolder& run, bool stopped) {
  const std::size_t recorded = run.recorded().size();
  if (result.counts.iterations >= recorded) return;
  throw ReplayMismatch(
      stopped ? "interrupted while replaying the records; the run folder is as it was"
              : "cannot resume: the sequence ended (or --max-scans stopped it) after " +
                    std::to_string(result.counts.iterations) + " scans, but " +
                    run.Path("iterations.jsonl") + " holds " + std::to_string(recorded) +
                    " records: is it the same log?");
}

}  // namespace

SessionRun RunSession(IterationSource& source, const SessionFactory& make_session, RunFolder& run,
                      const SessionRunOptions& options) {
  SessionRun result;
  const auto start = Clock::now();
  const double cpu_start_s = ProcessCpuSeconds();
  auto last_progress = start;
  Iteration iteration;
  auto wanted = [&] {
    return options.max_scans == 0 || result.counts.iterations < options.max_scans;
  };
  auto stopped = [&] { return options.stop != nullptr && options.stop->load(); };
  if (options.occupancy_grid) result.grid.emplace(*options.occupancy_grid);
  std::vector<std::size_t> grid_records;  // the record index of each scan the grid kept
  try {
    for (std::size_t skipped = 0; skipped < options.skip_scans && source.Next(iteration);)
      ++skipped;
    while (!stopped() && wanted() && source.Next(iteration)) {
      if (!result.session) result.session = make_session(source);
      result.counts.replayed += result.counts.iterations < run.recorded().size();
      const IterationRecord record =
          ProcessOne(*result.session, iteration, run, result.counts.iterations);
      if (result.grid && CastIntoGrid(record.validated, record.first)) {
        result.grid->AddScan(iteration.scan,
                             result.session->mounting().LaserPose(record.T_world_robot));
        grid_records.push_back(record.index);
      }
      result.counts.Add(record);
      if (options.progress && Clock::now() - last_progress > std::chrono::seconds(2)) {
        last_progress = Clock::now();
        PrintProgress(result, source, SecondsSince(start), record.map_points);
      }
    }
  } catch (const ReplayMismatch&) {
    throw;
  } catch (const std::exception& e) {
    // An error while replaying (the reader's, say) means the log is not the one recorded.
    if (result.counts.iterations < run.recorded().size())
      throw ReplayMismatch(std::string("cannot resume: ") + e.what());
    result.counts.failure = e.what();
  }
  if (options.progress) std::fprintf(stderr, "\n");
  RequireReplayDone(result, run, stopped());
  if (result.session) {
    result.session->Finish();
    if (result.grid) MoveToCorrectedPostures(*result.session, grid_records, *result.grid);
  }
  result.counts.interrupted = stopped();
  result.counts.wall_s = SecondsSince(start);
  result.counts.cpu_s = ProcessCpuSeconds() - cpu_start_s;
  return result;
}

LaserMounting ChooseMounting(const LaserMounting& from_source, const LaserMounting& configured,
                             bool source_overridden) {
  const Pose2D& T = configured.T_robot_laser;
  const bool configured_sets_one = T.x_m != 0.0 || T.y_m != 0.0 || T.yaw_rad != 0.0;
  return source_overridden || !configured_sets_one ? from_source : configured;
}

nlohmann::json SummaryJson(const SessionRun& run, const IterationSource& source) {
  const SessionCounts& c = run.counts;
  const double wall_s = c.wall_s;
  nlohmann::json summary = {
      {"interrupted", c.interrupted},
      {"iterations", c.iterations},
      {"localised", c.localised},
      {"skipped", c.skipped},
      {"validated", c.validated},
      {"flagged_not_validated", c.flagged},
      {"inserted", c.inserted},
      {"lost_stretches", c.lost_stretches},
      {"wide_searches", c.searches},
      {"localised_without_odometry", c.without_odometry},
      {"motion_searches", c.motion_searches},
      {"odometry_frozen_scans", c.odometry_frozen},
      {"odometry_from_scans", c.odometry_from_scans},
      {"recoveries", c.recoveries},
      {"refused_corrections", c.refused_corrections},
      {"slide_refusals", c.slide_refusals},
      {"new_ground_insertions", c.new_ground},
      {"turns_disputed_by_closures", c.disputed_turns},
      {"tighter_refinements_kept", c.tighter_refinements},
      {"lost_at_end", c.was_lost},
      {"map_points", run.session ? run.session->point_map().live_size() : 0},
      {"wall_time_s", wall_s},
      {"data_span_s", c.span_s()},
      {"first_timestamp_s", c.first_timestamp_s},
      {"scans_per_s", wall_s > 0 ? static_cast<double>(c.iterations) / wall_s : 0.0},
      {"times_real_time", wall_s > 0 ? c.span_s() / wall_s : 0.0},
      {"cpu_time_s", c.cpu_s},
      {"times_real_time_on_cpu", c.cpu_s > 0 ? c.span_s() / c.cpu_s : 0.0},
      {"peak_resident_mb", PeakResidentMegabytes()},
      {"odometry_reversed_increments", source.repaired_odometry_increments()},
      {"timestamps_not_increasing", source.timestamp_warnings()},
      {"timestamps_zero", source.zero_timestamps()},
      {"no_return_m", Nullable(source.no_return_m())},
      {"no_return_recognised_m", Nullable(source.recognised_no_return_m())},
      {"skipped_messages", source.skipped_messages()},
      {"laser_offsets_ignored", source.ignored_laser_offsets()}};
  if (c.iterations == 0) summary["problem"] = "the sequence has no scan";
  if (MostlyUnconfirmed(c))
    summary["problem"] = "most localised scans were not confirmed by the Likelihood Test";
  if (c.localisation) AddLocalisationSummary(c, summary);
  if (const auto signature = run.session ? run.session->map_signature() : std::nullopt) {
    summary["map_signature"] = {{"max_expect_value_m", signature->max_expect_value_m},
                                {"median_expect_value_m", signature->median_expect_value_m},
                                {"scans", signature->scans},
                                {"learned", signature->learned},
                                {"samples", SignatureSamples(*signature)}};
    summary["map_signature_wall_s"] = signature->wall_s;  // a timing, beside the others
  }
  if (const OdometryCalibration* calibration =
          run.session ? run.session->odometry_calibration() : nullptr)
    summary["odometry_calibration"] = OdometryCalibrationSummary(*calibration);
  if (run.session && run.session->pose_graph()) {
    const PoseGraph& graph = *run.session->pose_graph();
    summary["loop_closure"] = {{"nodes", graph.nodes().size()},
                               {"closures_tried", c.closures_tried},
                               {"closures_accepted", c.closures_accepted},
                               {"closures_kept", ClosuresKept(graph)},
                               {"map_renders", c.map_renders}};
    if (const OdometryModel* model = run.session->odometry_model())
      summary["loop_closure"]["odometry_model"] = OdometryModelSummary(*model, graph);
    if (const std::optional<FinalMatchSummary> m = run.session->final_match()) {
      summary["loop_closure"]["final_match"] = {{"matched", m->matched},
                                                {"joined", m->joined},
                                                {"solve_iterations", m->solve_iterations},
                                                {"largest_shift_m", m->largest_shift_m}};
      if (m->from_neighbours > 0) {  // loop_closure.final_match_neighbour_sigmas on
        summary["loop_closure"]["final_match"]["from_neighbours"] = m->from_neighbours;
        summary["loop_closure"]["final_match"]["took_neighbours"] = m->took_neighbours;
      }
      summary["final_match_wall_s"] = m->wall_s;  // a timing, beside the others
    }
  }
  if (c.replayed > 0) summary["resumed_after_records"] = c.replayed;
  if (!c.failure.empty()) summary["failed"] = c.failure;
  return summary;
}

}  // namespace scanloc
