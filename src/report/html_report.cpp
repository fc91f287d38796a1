#include "scanloc/report/html_report.hpp"

#include <filesystem>
#include <map>
#include <set>
#include <sstream>

#include "scanloc/common/atomic_file.hpp"
#include "scanloc/maps/point_map_io.hpp"
#include "scanloc/report/closure_figure.hpp"
#include "scanloc/report/grid_trajectory_figure.hpp"
#include "scanloc/report/histogram_figure.hpp"
#include "scanloc/report/html_tables.hpp"
#include "scanloc/report/map_figure.hpp"
#include "scanloc/report/markup.hpp"
#include "scanloc/report/scan_replay.hpp"
#include "scanloc/report/series_figure.hpp"
#include "scanloc/report/svg_canvas.hpp"
#include "scanloc/report/trajectory_figure.hpp"

namespace scanloc {
namespace {

constexpr const char* kStyle = R"css(
body { font: 14px/1.45 system-ui, sans-serif; color: #222; margin: 0 auto; padding: 0 20px 40px;
       max-width: 1320px; }
h1 { font-size: 22px; margin: 18px 0 4px; }
h2 { font-size: 18px; margin: 30px 0 8px; border-bottom: 1px solid #ccc; padding-bottom: 3px; }
h3 { font-size: 15px; margin: 0 0 6px; }
nav a { margin-right: 14px; }
.subtitle { color: #555; margin: 0 0 10px; word-break: break-all; }
.notes { background: #fff6e0; border: 1px solid #e8c36a; padding: 8px 12px 8px 28px; }
.message { color: #8a5a00; font-style: italic; }
.note { color: #666; font-size: 12px; margin: 4px 0 10px; }
figure { margin: 0 18px 12px 0; display: inline-block; vertical-align: top; }
figcaption { font-size: 12px; color: #555; max-width: 600px; }
svg { display: block; background: #fff; }
.figures { display: flex; flex-wrap: wrap; align-items: flex-start; }
section.iteration { border: 1px solid #ddd; border-left: 6px solid #bbb; padding: 10px 14px;
                    margin: 16px 0; }
section.iteration.validated { border-left-color: #1a9850; }
section.iteration.flagged { border-left-color: #d73027; }
.badge { display: inline-block; padding: 0 7px; border-radius: 8px; font-size: 12px;
         color: #fff; background: #888; margin-left: 6px; }
.badge.validated { background: #1a9850; }
.badge.flagged { background: #d73027; }
.facts { margin: 2px 0 8px; color: #333; }
table { border-collapse: collapse; margin: 6px 0; font-size: 12.5px; }
th, td { border: 1px solid #ddd; padding: 2px 7px; text-align: left; vertical-align: middle; }
th { background: #f3f3f3; font-weight: 600; }
td.n { text-align: right; font-variant-numeric: tabular-nums; }
table.summary th { width: 260px; }
tr.invalid td { color: #a02020; }
tr.chosen td { font-weight: 600; }
table.iterations tr.flagged td { background: #fdf0ef; }
table.iterations tr.skipped td { color: #888; }
details > summary { cursor: pointer; margin: 6px 0; }
pre { background: #f7f7f7; padding: 8px; overflow-x: auto; font-size: 12px; }
.zoomable { margin: 0 0 12px; }
.zoomable > label { font-size: 12px; margin-right: 10px; }
.zoom-view { --z: 1; overflow: auto; resize: both; border: 1px solid #ccc; max-width: 100%; }
.zoomable input.z2:checked ~ .zoom-view { --z: 2; }
.zoomable input.z4:checked ~ .zoom-view { --z: 4; }
.zoomable input.z8:checked ~ .zoom-view { --z: 8; }
.zoomable input.z16:checked ~ .zoom-view { --z: 16; }
.zoom-view > svg { width: calc(var(--w) * var(--z)); height: calc(var(--h) * var(--z)); }
.zoom-view > svg * { vector-effect: non-scaling-stroke; }
.zoom-view > svg text { font-size: calc(10px / var(--z)); }
.zoom-view > svg g.marker circle { r: calc(5px / var(--z)); }
.zoom-view > svg g.flag circle { r: calc(2px / var(--z)); }
)css";

std::string Escape(const std::string& text) {
  return EscapeMarkup(text);
}

std::string Pose(const Pose2D& p) {
  return "x " + FormatFixed(p.x_m, 3) + " m, y " + FormatFixed(p.y_m, 3) + " m, θ " +
         FormatFixed(p.yaw_rad, 4) + " rad";
}

std::vector<Eigen::Vector2d> Points(const PointMap& map) {
  std::vector<Eigen::Vector2d> points;
  points.reserve(map.live_size());
  for (std::size_t i = 0; i < map.size(); ++i)
    if (map.alive(i)) points.push_back(map.point(i));  // carved points are gone
  return points;
}

// What is known of an iteration in one line: timing, origin, reason, chosen, correction.
std::string Facts(const IterationRow& row) {
  std::ostringstream out;
  out << "t = " << FormatFixed(row.timestamp_s, 3) << " s";
  if (!row.origin.empty()) out << " · " << Escape(row.origin);
  if (row.flagged()) out << " · <b>" << Escape(row.reason) << "</b>";
  if (!row.chosen.empty()) out << " · chosen: " << Escape(row.chosen);
  out << "<br>odometry prediction: " << Escape(Pose(row.prediction))
      << "<br>kept posture: " << Escape(Pose(row.T_world_robot))
      << (row.flagged() && row.refinement ? " (the prediction: the refined fit was not validated)"
                                          : "");
  out << "<br>map: " << row.map_points << " points after this iteration"
      << (row.inserted ? " (this scan was inserted)" : "") << " · time: evaluate "
      << FormatFixed(row.evaluate_ms, 2) << " ms, refine " << FormatFixed(row.refine_ms, 2)
      << " ms, insert " << FormatFixed(row.insert_ms, 2) << " ms, total "
      << FormatFixed(row.total_ms, 2) << " ms";
  return out.str();
}

struct IterationFigures {
  std::string overview, close_up, caption;
};

std::string IterationSection(const IterationRow& row, const IterationFigures& figures,
                             double slot_width_m) {
  const std::string id = "iteration-" + std::to_string(row.index);
  std::ostringstream out;
  out << "<section class=\"iteration " << row.status() << "\" id=\"" << id << "\">\n<h3>Iteration "
      << row.index << "<span class=\"badge " << row.status() << "\">" << row.status()
      << "</span></h3>\n<p class=\"facts\">" << Facts(row) << "</p>\n<div class=\"figures\">\n"
      << "<figure>" << figures.overview << "<figcaption>" << Escape(figures.caption)
      << "</figcaption></figure>\n";
  if (!figures.close_up.empty())
    out << "<figure>" << figures.close_up
        << "<figcaption>Close-up of the candidates, same symbols.</figcaption></figure>\n";
  if (row.refinement) {
    out << "<figure>"
        << HistogramFigure(row.refinement->before, &row.refinement->after, slot_width_m,
                           id + "-histogram")
        << "<figcaption>Point-to-point distances of the chosen candidate before (dark, behind) "
           "and after refinement (light, in front), as the chapter's Figures 12 and 15. Columns "
           "to the left are close fits.</figcaption></figure>\n";
  } else if (const CandidateRow* chosen = row.chosen_candidate()) {
    out << "<figure>" << HistogramFigure(chosen->test, nullptr, slot_width_m, id + "-histogram")
        << "<figcaption>Point-to-point distances of the chosen candidate (not "
           "refined).</figcaption></figure>\n";
  }
  out << "</div>\n" << CandidateTable(row, id) << RefinementTable(row);
  for (const std::string& problem : row.problems)
    out << "<p class=\"message\">" << Escape(problem) << "</p>\n";
  out << "</section>\n";
  return out.str();
}

// The selected iterations' map figures: with their scans and the map rebuilt up to them when
// the sequence can be read, else over the final map.
std::map<std::size_t, IterationFigures> DrawIterations(const RunContents& run,
                                                       const IterationSelection& selection,
                                                       ReportResult& result) {
  const std::vector<IterationRow>& rows = run.iterations.rows;
  std::map<std::size_t, IterationFigures> figures;
  const LaserMounting& mounting = run.config.mounting;
  auto draw = [&](const IterationRow& row, const LaserScan* scan,
                  const std::vector<Eigen::Vector2d>& map_points, const std::string& map_label,
                  const std::string& map_note) {
    IterationFigureInput input;
    input.row = &row;
    input.map_points = &map_points;
    input.line_map = &run.line_map;
    input.scan = scan;
    input.mounting = mounting;
    input.map_label = map_label;
    IterationFigures& out = figures[row.index];
    const std::string id = "map-" + std::to_string(row.index);
    out.overview = IterationMapFigure(input, id);
    if (!row.candidates.empty()) {
      input.view = IterationView::kCandidates;
      out.close_up = IterationMapFigure(input, id + "-close");
    }
    out.caption =
        "The candidate postures of the robot (arrows: green valid, red invalid; hover for the "
        "moments) and the odometry prediction (ring)";
    out.caption += !out.close_up.empty() ? ", over the scan and, right, close up. " : ". ";
    out.caption += scan ? std::string("The scan (orange) is drawn at ") +
                              (row.refinement ? "the chosen candidate's refined posture"
                                              : "the posture kept for this iteration") +
                              "; grey: " + map_label + map_note + "."
                        : "The scan is unavailable (see the notes at the top); grey: " + map_label +
                              map_note + ".";
  };
  if (!run.log_path.empty() && !selection.indices.empty()) {
    PointMap map(run.config.point_map);
    if (!run.point_map_path.empty()) {
      try {
        map = LoadPointMapPcd(run.point_map_path, run.config.point_map);
      } catch (const std::exception& e) {
        result.notes.push_back(std::string("the initial point map could not be read: ") + e.what());
      }
    }
    const ScanReplayResult replay = ReplayScans(
        run.log_path, rows, selection.indices, mounting, run.config.session.extension, map,
        [&](const IterationRow& row, const LaserScan& scan, const PointMap& map_before) {
          // The session's own count after the previous iteration, to compare.
          std::string note = ", rebuilt from the scans inserted so far: " +
                             std::to_string(map_before.live_size()) + " points";
          if (row.index > 0)
            note +=
                " (the session's map had " + std::to_string(rows[row.index - 1].map_points) + ")";
          draw(row, &scan, Points(map_before), "the map before this scan (rebuilt)", note);
        });
    result.drawn_with_scan = replay.scans_visited;
    if (!replay.problem.empty())
      result.notes.push_back(replay.problem +
                             " — iterations from there on are drawn without "
                             "their scans, over the final map");
  }
  for (const std::size_t index : selection.indices)
    if (!figures.count(index)) draw(rows[index], nullptr, run.final_map, "the final map", "");

  return figures;
}

// The page's head, title, navigation and notes.
void WritePageHead(std::ostream& page, const RunContents& run, const ReportResult& result) {
  const std::string name = std::filesystem::path(run.directory).filename().string();
  page << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
       << "<meta name=\"viewport\" content=\"width=device-width, initial-scale=1\">\n"
       << "<title>scanloc report: " << Escape(name) << "</title>\n<style>" << kStyle
       << "</style>\n</head>\n<body>\n"
       << "<h1>scanloc session report</h1>\n<p class=\"subtitle\">run folder "
       << Escape(run.directory)
       << (run.log_path.empty() ? "" : " · sequence " + Escape(run.log_path))
       << "</p>\n<nav><a href=\"#summary\">Summary</a><a href=\"#trajectory\">Trajectory</a>"
       << "<a href=\"#moments\">Moments</a><a href=\"#iterations\">Iterations drawn</a>"
       << "<a href=\"#all\">All iterations</a></nav>\n";
  if (!result.notes.empty()) {
    page << "<ul class=\"notes\">\n";
    for (const std::string& note : result.notes) page << "<li>" << Escape(note) << "</li>\n";
    page << "</ul>\n";
  }
}

// The trajectory over the occupancy grid, a pixel per cell, zoomed by radio buttons and CSS alone
// (the page has no script): strokes, markers and labels keep their size on screen.
void WriteGridTrajectoryFigure(std::ostream& page, const RunContents& run,
                               const TrajectoryFigureInput& trajectory) {
  const OccupancyGridImage& grid = *run.grid;
  const GridTrajectoryFigure figure = TrajectoryOverGridFigure(trajectory, grid, "trajectory-grid");
  page << "<figure class=\"zoomable\">";
  for (const int zoom : {1, 2, 4, 8, 16}) {
    const std::string id = "trajectory-zoom-" + std::to_string(zoom);
    page << "<input type=\"radio\" name=\"trajectory-zoom\" class=\"z" << zoom << "\" id=\"" << id
         << "\"" << (zoom == 1 ? " checked" : "") << "><label for=\"" << id << "\">" << zoom
         << "×</label>";
  }
  page << "<div class=\"zoom-view\" style=\"--w: " << SvgNumber(figure.width_px)
       << "px; --h: " << SvgNumber(figure.height_px)
       << "px; width: " << SvgNumber(figure.width_px + 2)
       << "px; height: " << SvgNumber(figure.height_px + 2) << "px\">" << figure.svg << "</div>"
       << figure.legend
       << "<figcaption>The posture kept for every iteration (blue), the flagged ones (red), and "
          "the iterations drawn below (numbered rings, linked to their sections; a number that "
          "would cover an earlier one is left out, its ring keeps the tooltip), over the "
          "session's occupancy grid (map.pgm: "
       << grid.width << " × " << grid.height << " cells of "
       << FormatFixed(100 * grid.resolution_m, 1)
       << " cm, a pixel per cell). Zoom with the buttons, scroll or drag the corner to resize "
          "the view.</figcaption></figure>\n";
}

// The trajectory over the final map (its occupancy grid when the run has one), and close up on
// map.pcd's points when that shows more.
void WriteTrajectorySection(std::ostream& page, const RunContents& run,
                            const IterationSelection& selection) {
  TrajectoryFigureInput trajectory;
  trajectory.rows = &run.iterations.rows;
  trajectory.map_points = &run.final_map;
  trajectory.line_map = &run.line_map;
  trajectory.linked = selection.indices;
  page << "<h2 id=\"trajectory\">Trajectory over the final map</h2>\n";
  if (run.grid) WriteGridTrajectoryFigure(page, run, trajectory);
  page << "<div class=\"figures\">\n<figure>";
  page << TrajectoryFigure(trajectory, "trajectory-points")
       << "<figcaption>The posture kept for every iteration (blue), the flagged ones (red), and "
          "the iterations drawn below (numbered rings, linked to their sections), over the "
          "final map ("
       << run.final_map.size() << " points).</figcaption></figure>\n";
  if (TrajectoryCloseUpWorthwhile(trajectory)) {
    trajectory.close_up = true;
    page << "<figure>" << TrajectoryFigure(trajectory, "trajectory-close")
         << "<figcaption>The same, close up on the trajectory.</figcaption></figure>\n";
  }
  page << "</div>\n";
}

// EV and MP/NVP of every localised iteration against the rules' bounds.
void WriteMomentsSection(std::ostream& page, const RunContents& run) {
  const std::vector<IterationRow>& rows = run.iterations.rows;
  const ValidationOptions& session_rules = run.config.validation;  // as the session applied them
  page << "<h2 id=\"moments\">Moments over the session</h2>\n<figure>"
       << MomentSeriesFigure(rows, session_rules, "moments")
       << "<figcaption>For every localised iteration, the expected value (3.9) and the match "
          "ratio MP/NVP of its final posture (after refinement), against rule 2's E_max = "
       << FormatFixed(100.0 * session_rules.max_expect_value_m, 1)
       << " cm and rule 1's minimum ratio " << FormatFixed(session_rules.min_match_ratio, 2)
       << ".</figcaption></figure>\n";
}

// With loop closure on: every closure matched against the old nodes, and what it corrected.
void WriteClosureSection(std::ostream& page, const std::vector<IterationRow>& rows) {
  std::size_t tried = 0, accepted = 0;
  for (const IterationRow& row : rows)
    if (row.closure) {
      ++tried;
      accepted += row.closure->accepted;
    }
  if (tried == 0) return;
  const std::size_t matched = ClosureSamples(rows).size();
  page << "<h2 id=\"closures\">Loop closures</h2>\n<figure>"
       << ClosureCorrectionFigure(rows, "closures")
       << "<figcaption>" << tried << " closures tried, " << matched
       << " matched against the old nodes, " << accepted
       << " accepted. For each matched one: how far the match put the scan from the session's "
          "posture (top) and how much it turned it (bottom); for the accepted ones, a ring at the "
          "largest node displacement of the pose graph's solve that followed. Hover a point for "
          "its scans.</figcaption></figure>\n";
}

}  // namespace

std::string RenderRunReport(const RunContents& run, const ReportOptions& options,
                            ReportResult& result) {
  const std::vector<IterationRow>& rows = run.iterations.rows;
  const IterationSelection selection = SelectIterations(rows, options.selection);
  result.iterations = rows.size();
  result.drawn = selection.indices.size();
  result.selection_rule = selection.rule;
  result.notes = run.notes;
  std::map<std::size_t, IterationFigures> figures = DrawIterations(run, selection, result);

  std::ostringstream page;
  WritePageHead(page, run, result);
  page << "<h2 id=\"summary\">Session summary</h2>\n" << SummaryTable(run.summary, rows);
  if (const auto it = run.summary.find("config"); it != run.summary.end())
    page << "<details><summary>Configuration of the session</summary><pre>" << Escape(it->dump(2))
         << "</pre></details>\n";

  WriteTrajectorySection(page, run, selection);
  WriteMomentsSection(page, run);
  WriteClosureSection(page, rows);
  page << "<h2 id=\"iterations\">Iterations drawn</h2>\n<p>Selection: " << Escape(selection.rule)
       << ". Change it with <code>--first N</code>, <code>--every K</code>, <code>--flagged "
          "N</code> and <code>--iterations 3,10-12</code>.</p>\n";
  if (selection.indices.empty()) page << "<p class=\"message\">No iteration was selected.</p>\n";
  const double slot_width_m = run.config.scoring.test.slot_width_m;
  for (const std::size_t index : selection.indices)
    page << IterationSection(rows[index], figures[index], slot_width_m);

  const std::set<std::size_t> drawn(selection.indices.begin(), selection.indices.end());
  page << "<h2 id=\"all\">All iterations</h2>\n<details" << (rows.size() <= 200 ? " open" : "")
       << "><summary>" << rows.size()
       << " iterations (click to show or hide); numbers link to the iterations drawn</summary>\n"
       << IterationsTable(rows, drawn) << "</details>\n</body>\n</html>\n";
  return page.str();
}

ReportResult WriteRunReport(const std::string& run_directory, const ReportOptions& options) {
  const RunContents run = ReadRunContents(run_directory, options.inputs);
  ReportResult result;
  const std::string html = RenderRunReport(run, options, result);
  result.path = options.output_path.empty() ? run_directory + "/report.html" : options.output_path;
  WriteFileAtomically(result.path, [&html](std::ostream& out) { out << html; });
  result.bytes = html.size();
  return result;
}

}  // namespace scanloc
