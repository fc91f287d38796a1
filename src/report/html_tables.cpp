#include "scanloc/report/html_tables.hpp"

#include <cmath>
#include <sstream>

#include "scanloc/report/histogram_figure.hpp"
#include "scanloc/report/markup.hpp"
#include "scanloc/report/series_figure.hpp"

namespace scanloc {
namespace {

using nlohmann::json;

std::string Td(const std::string& text, const char* css_class = nullptr) {
  return std::string("<td") + (css_class ? std::string(" class=\"") + css_class + "\"" : "") + ">" +
         EscapeMarkup(text) + "</td>";
}

std::string Num(double value, int decimals) {
  return Td(FormatFixed(value, decimals), "n");
}

std::string Int(long long value) {
  return Td(std::to_string(value), "n");
}

std::string Centimetres(double metres) {
  return Num(100.0 * metres, 2);
}

std::string Header(const std::vector<std::string>& names) {
  std::string out = "<thead><tr>";
  for (const std::string& name : names) out += "<th>" + EscapeMarkup(name) + "</th>";
  return out + "</tr></thead>\n";
}

// A summary value for people: numbers rounded, booleans as yes/no, arrays and objects as JSON.
std::string SummaryValue(const json& value) {
  if (value.is_null()) return "none";
  if (value.is_boolean()) return value.get<bool>() ? "yes" : "no";
  if (value.is_number_integer() || value.is_number_unsigned()) return value.dump();
  if (value.is_number()) return FormatFixed(value.get<double>(), 3);
  if (value.is_string()) return value.get<std::string>();
  return value.dump();
}

// "scan 0: ambiguous (2) → scan 6: confirmed (1) [discarded (x, y, θ): why]", the first 20
// changes.
std::string HypothesesOverTime(const json& series) {
  if (!series.is_array()) return SummaryValue(series);
  std::string text;
  for (std::size_t i = 0; i < series.size() && i < 20; ++i) {
    const json& p = series[i];
    text += (i > 0 ? " → " : "") + std::string("scan ") + SummaryValue(p.value("scan", json())) +
            ": " + SummaryValue(p.value("state", json())) + " (" +
            SummaryValue(p.value("hypotheses", json())) + ")";
    const json discarded = p.value("discarded", json::array());
    for (std::size_t k = 0; discarded.is_array() && k < discarded.size(); ++k)
      text += (k == 0 ? " [discarded " : "; ") + SummaryValue(discarded[k]) +
              (k + 1 == discarded.size() ? "]" : "");
  }
  if (series.size() > 20) text += " … (" + std::to_string(series.size()) + " changes in all)";
  return text;
}

std::string VerdictClass(bool valid) {
  return valid ? "valid" : "invalid";
}

}  // namespace

std::string SummaryTable(const json& summary, const std::vector<IterationRow>& rows) {
  std::size_t localised = 0, skipped = 0, validated = 0, flagged = 0, inserted = 0;
  // Counted as the session counts them (its summary line and summary.json).
  for (const IterationRow& row : rows) {
    localised += !row.skipped;
    skipped += row.skipped;
    validated += row.validated;
    flagged += row.flagged();
    inserted += row.inserted;
  }
  std::ostringstream out;
  out << "<table class=\"summary\">\n<tbody>\n";
  auto line = [&](const std::string& name, const std::string& value) {
    out << "<tr><th>" << EscapeMarkup(name) << "</th>" << Td(value) << "</tr>\n";
  };
  line("iterations", std::to_string(rows.size()));
  line("localised (not skipped)", std::to_string(localised));
  line("skipped (robot had not moved)", std::to_string(skipped));
  line("validated", std::to_string(validated));
  line("flagged (localised, not validated)", std::to_string(flagged));
  line("inserted into the map", std::to_string(inserted));
  if (!rows.empty()) {
    line("map points at the end", std::to_string(rows.back().map_points));
    line("time span of the data",
         FormatFixed(rows.back().timestamp_s - rows.front().timestamp_s, 1) + " s");
  }
  // What only summary.json knows, in a fixed order; other keys follow as they come.
  static const char* const kKnown[][2] = {
      {"log", "sequence"},
      {"interrupted", "interrupted"},
      {"wall_time_s", "wall time [s]"},
      {"scans_per_s", "scans per second"},
      {"times_real_time", "× real time"},
      {"cpu_time_s", "CPU time, user + system [s]"},
      {"times_real_time_on_cpu", "× real time on CPU"},
      {"peak_resident_mb", "peak memory [MB]"},
      {"lost_stretches", "times lost"},
      {"wide_searches", "wide searches"},
      {"recoveries", "recoveries"},
      {"refused_corrections", "corrections refused"},
      {"slide_refusals", "corrections refused as a slide"},
      {"turns_disputed_by_closures", "turns disputed by closures"},
      {"tighter_refinements_kept", "tighter refinements kept over the rules' best"},
      {"localised_without_odometry", "scans localised without odometry"},
      {"motion_searches", "searches over the motion seen lately"},
      {"odometry_frozen_scans", "scans whose odometry had not moved while the ranges did"},
      {"odometry_from_scans", "scans moved by their match on the scan before (no odometry)"},
      {"lost_at_end", "lost at the end"},
      {"first_confirmed_scan", "first confirmed scan"},
      {"seconds_to_confirm", "seconds to confirm"},
      {"ambiguous_scans", "ambiguous scans"},
      {"max_hypotheses", "hypotheses at most"},
      {"scans_without_posture", "scans without a posture"},
      {"hypotheses_over_time", "hypotheses over time"},
      {"loop_closure", "loop closure"},
      {"problem", "problem"}};
  for (const auto& [key, name] : kKnown)
    if (const auto it = summary.find(key); it != summary.end())
      line(name, std::string(key) == "hypotheses_over_time" ? HypothesesOverTime(*it)
                                                            : SummaryValue(*it));
  if (const auto it = summary.find("inputs"); it != summary.end() && it->is_object())
    for (const auto& [key, value] : it->items()) line("input: " + key, SummaryValue(value));
  out << "</tbody>\n</table>\n";
  return out.str();
}

std::string CandidateTable(const IterationRow& row, const std::string& id) {
  if (row.candidates.empty())
    return std::string("<p class=\"message\">") +
           (row.first ? "The first iteration: no map yet, nothing to test; the scan starts the map."
            : row.skipped
                ? "Not localised: the robot had not moved enough since the last localised scan."
                : "No candidate was tested.") +
           "</p>\n";
  std::ostringstream out;
  out << "<table class=\"candidates\">\n"
      << Header({"posture", "x [m]", "y [m]", "θ [rad]", "MP", "NVP", "MP/NVP", "EV [cm]",
                 "√Disp [cm]", "cost", "LD-EV [cm]", "histogram", "valid", "reason"})
      << "<tbody>\n";
  bool any_valid = false;
  for (std::size_t i = 0; i < row.candidates.size(); ++i) {
    const CandidateRow& c = row.candidates[i];
    any_valid |= c.valid;
    const bool chosen = c.label == row.chosen;
    out << "<tr class=\"" << VerdictClass(c.valid) << (chosen ? " chosen" : "") << "\">"
        << Td(c.label + (chosen ? " ◆" : "")) << Num(c.T_world_robot.x_m, 4)
        << Num(c.T_world_robot.y_m, 4) << Num(c.T_world_robot.yaw_rad, 5) << Int(c.test.match_pairs)
        << Int(c.test.valid_pairs) << Num(c.test.MatchRatio(), 3)
        << Centimetres(c.test.expect_value_m) << Centimetres(std::sqrt(c.test.dispersion_m2))
        << Num(c.cost.value_or(NAN), 4) << Centimetres(c.distance_expect_value_m.value_or(NAN))
        << "<td>" << HistogramSparkline(c.test.histogram, id + "-h" + std::to_string(i)) << "</td>"
        << Td(c.valid ? "yes" : "no") << Td(c.valid ? "rank " + std::to_string(c.rank) : c.reason)
        << "</tr>\n";
  }
  out << "</tbody>\n</table>\n";
  if (!any_valid)
    out << "<p class=\"message\">No candidate passed the validation rules"
        << (row.chosen.empty()
                ? ""
                : "; the cheapest by (3.11), " + EscapeMarkup(row.chosen) + ", was refined")
        << ".</p>\n";
  out << "<p class=\"note\">◆ the chosen candidate. MP: match pairs; NVP: valid pairs; EV and "
         "√Disp: (3.9) and (3.10); cost: (3.11); LD-EV: the Likelihood Distance's expected value "
         "(§3.5); the histogram's last slot in red.</p>\n";
  return out.str();
}

std::string RefinementTable(const IterationRow& row) {
  if (!row.refinement) return "";
  const RefinementRow& r = *row.refinement;
  const CandidateRow* chosen = row.chosen_candidate();
  std::ostringstream out;
  out << "<table class=\"refinement\">\n"
      << Header({"stage", "x [m]", "y [m]", "θ [rad]", "MP", "NVP", "MP/NVP", "EV [cm]",
                 "√Disp [cm]", "LD-EV [cm]"})
      << "<tbody>\n";
  auto stage = [&](const char* name, const Pose2D* pose, const LikelihoodTestResult& t,
                   const std::optional<double>& distance_ev) {
    out << "<tr>" << Td(name);
    if (pose)
      out << Num(pose->x_m, 4) << Num(pose->y_m, 4) << Num(pose->yaw_rad, 5);
    else
      out << Td("") << Td("") << Td("");
    out << Int(t.match_pairs) << Int(t.valid_pairs) << Num(t.MatchRatio(), 3)
        << Centimetres(t.expect_value_m) << Centimetres(std::sqrt(t.dispersion_m2))
        << Centimetres(distance_ev.value_or(NAN)) << "</tr>\n";
  };
  const Pose2D* before = chosen && chosen->T_world_laser ? &*chosen->T_world_laser : nullptr;
  stage("before (laser)", before, r.before, r.distance_expect_value_before_m);
  stage("after (laser)", &r.T_world_laser, r.after, r.distance_expect_value_after_m);
  out << "</tbody>\n</table>\n<p class=\"note\">";
  if (before) {
    const Pose2D& a = *before;
    const Pose2D& b = r.T_world_laser;
    out << "Correction: " << FormatFixed(1e3 * (b.x_m - a.x_m), 1) << " mm, "
        << FormatFixed(1e3 * (b.y_m - a.y_m), 1) << " mm, "
        << FormatFixed(1e3 * NormalizeAngle(b.yaw_rad - a.yaw_rad), 2) << " mrad. ";
  }
  out << (r.converged ? "Converged" : "Not converged") << " after " << r.iterations
      << " iterations, " << FormatFixed(1e3 * r.time_s, 2) << " ms.";
  if (r.degenerate) out << " Degenerate: " << EscapeMarkup(r.degeneracy) << ".";
  out << "</p>\n";
  if (!row.refined_candidates.empty()) {
    out << "<table class=\"refined\">\n"
        << Header({"refined candidate", "x [m]", "y [m]", "θ [rad]", "MP/NVP", "EV [cm]", "cost",
                   "valid", "reason"})
        << "<tbody>\n";
    for (const RefinedCandidateRow& c : row.refined_candidates)
      out << "<tr class=\"" << VerdictClass(c.valid) << "\">" << Td(c.candidate)
          << Num(c.T_world_laser.x_m, 4) << Num(c.T_world_laser.y_m, 4)
          << Num(c.T_world_laser.yaw_rad, 5) << Num(c.match_ratio.value_or(NAN), 3)
          << Centimetres(c.expect_value_m.value_or(NAN)) << Num(c.cost.value_or(NAN), 4)
          << Td(c.valid ? "yes" : "no") << Td(c.valid ? "rank " + std::to_string(c.rank) : c.reason)
          << "</tr>\n";
    out << "</tbody>\n</table>\n";
  }
  return out.str();
}

std::string IterationsTable(const std::vector<IterationRow>& rows,
                            const std::set<std::size_t>& drawn) {
  std::ostringstream out;
  out << "<table class=\"iterations\">\n"
      << Header({"#", "t [s]", "status", "reason", "candidates (valid)", "chosen", "MP/NVP",
                 "EV [cm]", "x [m]", "y [m]", "θ [rad]", "map points", "time [ms]"})
      << "<tbody>\n";
  for (const IterationRow& row : rows) {
    std::size_t valid = 0;
    for (const CandidateRow& c : row.candidates) valid += c.valid;
    const LikelihoodTestResult* test = FinalTest(row);
    const std::string index = std::to_string(row.index);
    out << "<tr class=\"" << row.status() << "\">"
        << (drawn.count(row.index)
                ? "<td class=\"n\"><a href=\"#iteration-" + index + "\">" + index + "</a></td>"
                : Int(static_cast<long long>(row.index)))
        << Num(row.timestamp_s, 3)
        << Td(std::string(row.status()) + (row.searched ? ", searched wide" : "") +
              (row.recovered ? ", recovered"
               : row.lost    ? ", lost"
                             : "") +
              (row.state.empty() ? std::string()
                                 : ", " + row.state + " (" + std::to_string(row.hypotheses) +
                                       (row.hypotheses == 1 ? " hypothesis)" : " hypotheses)")))
        << Td(row.flagged() ? row.reason : std::string())
        << Td(row.candidates.empty()
                  ? std::string()
                  : std::to_string(row.candidates.size()) + " (" + std::to_string(valid) + ")")
        << Td(row.chosen) << (test ? Num(test->MatchRatio(), 3) : Td(""))
        << (test ? Centimetres(test->expect_value_m) : Td("")) << Num(row.T_world_robot.x_m, 3)
        << Num(row.T_world_robot.y_m, 3) << Num(row.T_world_robot.yaw_rad, 4)
        << Int(static_cast<long long>(row.map_points)) << Num(row.total_ms, 2) << "</tr>\n";
  }
  out << "</tbody>\n</table>\n";
  return out.str();
}

}  // namespace scanloc
