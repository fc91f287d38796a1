#pragma once
// A whole session over a recorded sequence, into a run folder: the loop, what it counts, the
// operator's progress line, and the summary. An error mid-run (a malformed line at scan 103, a
// truncated file) ends the loop but not the run: what was done is still written, and the summary
// says the run failed and why.

#include <atomic>
#include <functional>
#include <memory>
#include <nlohmann/json_fwd.hpp>
#include <optional>
#include <string>
#include <vector>

#include "scanloc/io/run_folder.hpp"
#include "scanloc/maps/occupancy_grid.hpp"
#include "scanloc/session/iteration.hpp"
#include "scanloc/session/session.hpp"

namespace scanloc {

struct SessionRunOptions {
  std::size_t max_scans = 0;                // stop after this many scans (0: all)
  bool progress = true;                     // a progress line on stderr every 2 s
  const std::atomic<bool>* stop = nullptr;  // when set (Ctrl-C), the loop ends early
  // When set, the scans CastIntoGrid picks (io/run_grid.hpp) are kept for an occupancy grid, at
  // the postures the session kept, corrected after the run as trajectory.tum is (loop closure).
  std::optional<OccupancyGridOptions> occupancy_grid;
  std::size_t skip_scans = 0;  // start after this many scans of the source
};

// What a run did, counted as it went.
struct SessionCounts {
  std::size_t iterations = 0, localised = 0, skipped = 0, validated = 0, flagged = 0, inserted = 0;
  // Stretches of scans the session was lost in, wide searches run, confirmations that ended one.
  std::size_t lost_stretches = 0, searches = 0, recoveries = 0;
  // Refinements the correction gate refused (the scan kept the odometry's prediction).
  std::size_t refused_corrections = 0;
  std::size_t slide_refusals = 0;  // confirmed corrections refused as a slide
  std::size_t new_ground = 0;      // unconfirmed scans that extended the map on new ground
  std::size_t disputed_turns = 0;  // corrections a closure's dispute withdrew
  // Scans that kept a tighter refinement than the rules' best (tighter_refinement.hpp).
  std::size_t tighter_refinements = 0;
  // Scans localised without odometry (none in the log, ignored, or frozen), those of them the map
  // was searched for over the motion seen lately, and those whose odometry had not moved since the
  // first scan while the ranges did.
  std::size_t without_odometry = 0, motion_searches = 0, odometry_frozen = 0;
  std::size_t odometry_from_scans = 0;  // scans given the scans' own odometry (ScanOdometry)
  bool was_lost = false;                // lost after the last scan
  // Localisation on a saved map: the first scan whose posture was confirmed (its index and time),
  // the scans with several hypotheses, the most held at once, the scans without a posture.
  bool localisation = false;  // the records carry a localisation's state
  std::optional<std::size_t> first_confirmed;
  double first_confirmed_timestamp_s = 0.0;
  std::size_t ambiguous = 0, max_hypotheses = 0, unposed = 0;
  // The hypotheses over time: a point at the first scan and wherever the state or the number of
  // hypotheses held changed.
  struct HypothesesPoint {
    std::size_t scan = 0;
    double timestamp_s = 0.0;
    std::string state;
    std::size_t hypotheses = 0;
    std::vector<std::string> discarded;  // the hypotheses discarded at that scan, and why
  };
  std::vector<HypothesesPoint> hypotheses_over_time;
  // Loop closure: closures tried, accepted, and the renders of the map they caused.
  std::size_t closures_tried = 0, closures_accepted = 0, map_renders = 0;
  double first_timestamp_s = 0.0, min_timestamp_s = 0.0, max_timestamp_s = 0.0;
  double wall_s = 0.0;
  double cpu_s = 0.0;  // user + system, every thread, over the same stretch as wall_s
  // Iterations replayed from the records of an interrupted run (--resume), not localised again.
  std::size_t replayed = 0;
  bool interrupted = false;  // stopped by options.stop
  std::string failure;       // why the run ended early on an error; "" when it did not

  double span_s() const { return max_timestamp_s - min_timestamp_s; }
  void Add(const IterationRecord& record);
};

// True when more than half of the localised scans were not confirmed (flagged).
bool MostlyUnconfirmed(const SessionCounts& counts);

// Builds the session when the first scan has been read: a source's mounting is final then
// (CARMEN's PARAM lines precede the first scan).
using SessionFactory = std::function<std::unique_ptr<ScanProcessor>(const IterationSource& source)>;

struct SessionRun {
  std::unique_ptr<ScanProcessor> session;  // null when the source had no scan
  SessionCounts counts;
  std::optional<OccupancyGridBuilder> grid;  // when options.occupancy_grid is set
};

// Processes the source's iterations one by one, recording each in `run`. When `run` was opened to
// resume, the iterations it holds records of are replayed first (ScanProcessor::Replay); a replay
// that disagrees with its record, or a sequence that ends before the records do, throws
// ReplayMismatch and leaves the folder as it was.
SessionRun RunSession(IterationSource& source, const SessionFactory& make_session, RunFolder& run,
                      const SessionRunOptions& options);

// The mounting in force: the source's, unless the configuration sets one and the command line did
// not override the source's (`source_overridden`, e.g. --laser-offset).
LaserMounting ChooseMounting(const LaserMounting& from_source, const LaserMounting& configured,
                             bool source_overridden);

// summary.json's counts, throughput and problems (the caller adds the configuration and inputs).
nlohmann::json SummaryJson(const SessionRun& run, const IterationSource& source);

}  // namespace scanloc
