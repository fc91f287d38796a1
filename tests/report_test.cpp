// Tests of the report layer: escaping, the SVG writer, plot frames, label placement, reading
// iterations.jsonl (with file:line errors), the selection of iterations, the figures, and whole
// pages for runs with missing pieces, an empty map and no valid candidate, and a real replay.

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <regex>

#include "report_fixtures.hpp"
#include "scanloc/common/parse_error.hpp"
#include "scanloc/io/run_folder.hpp"
#include "scanloc/maps/point_map_io.hpp"
#include "scanloc/report/grid_trajectory_figure.hpp"
#include "scanloc/report/histogram_figure.hpp"
#include "scanloc/report/html_report.hpp"
#include "scanloc/report/html_tables.hpp"
#include "scanloc/report/iteration_selection.hpp"
#include "scanloc/report/label_placer.hpp"
#include "scanloc/report/map_figure.hpp"
#include "scanloc/report/markup.hpp"
#include "scanloc/report/plot_frame.hpp"
#include "scanloc/report/png_image.hpp"
#include "scanloc/report/run_records.hpp"
#include "scanloc/report/scan_replay.hpp"
#include "scanloc/report/series_figure.hpp"
#include "scanloc/report/svg_canvas.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

using testing::ReadText;

using testing::Contains;

std::size_t Count(const std::string& text, const std::string& part) {
  std::size_t count = 0;
  for (std::size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1))
    ++count;
  return count;
}

// A label with every character HTML and SVG treat specially.
const std::string kNastyLabel = "<p1 & \"x\" 'y'>";
const std::string kNastyEscaped = "&lt;p1 &amp; &quot;x&quot; &#39;y&#39;&gt;";

// ---- markup and SVG ----------------------------------------------------------------------------

TEST(EscapeMarkup, EscapesTheFiveSpecialCharactersAndReplacesControlCharacters) {
  EXPECT_EQ(EscapeMarkup(kNastyLabel), kNastyEscaped);
  EXPECT_EQ(EscapeMarkup("a\x01"
                         "b\tc\n"),
            "a\xEF\xBF\xBD"
            "b\tc\n");
  EXPECT_EQ(EscapeMarkup("θ ≥ 19 cm"), "θ ≥ 19 cm");  // UTF-8 passes through
}

TEST(FormatFixed, RoundsAndShowsNonFiniteValuesAsADash) {
  EXPECT_EQ(FormatFixed(0.12345, 3), "0.123");
  EXPECT_EQ(FormatFixed(-0.0001, 2), "0.00");
  EXPECT_EQ(FormatFixed(NAN, 2), "\xE2\x80\x93");
  EXPECT_EQ(FormatBytes(1536.0), "1.5 kB");
}

TEST(SvgCanvas, TextTooltipsAndLinksAreEscaped) {
  SvgCanvas svg(100, 50, "fig", kNastyLabel);
  svg.BeginLink("#a\"b");
  svg.BeginGroup(kNastyLabel);
  svg.Text({10, 10}, kNastyLabel);
  svg.EndGroup();
  svg.EndLink();
  const std::string out = svg.Finish();
  EXPECT_FALSE(Contains(out, kNastyLabel));
  EXPECT_EQ(Count(out, kNastyEscaped), 3u);  // title, tooltip, text
  EXPECT_TRUE(Contains(out, "href=\"#a&quot;b\""));
  EXPECT_EQ(out.rfind("<svg ", 0), 0u);
  EXPECT_TRUE(Contains(out, "viewBox=\"0 0 100 50\""));
}

TEST(SvgCanvas, UnbalancedGroupsAndLinksAreRefused) {
  SvgCanvas open(10, 10, "a", "t");
  open.BeginGroup();
  EXPECT_THROW(open.Finish(), std::logic_error);
  SvgCanvas crossed(10, 10, "b", "t");
  crossed.BeginLink("#x");
  EXPECT_THROW(crossed.EndGroup(), std::logic_error);
  SvgCanvas closed(10, 10, "c", "t");
  EXPECT_THROW(closed.EndLink(), std::logic_error);
  EXPECT_THROW(SvgCanvas(0, 10, "d", "t"), std::invalid_argument);
}

TEST(SvgCanvas, DotsFallingOnTheSamePixelAreDrawnOnce) {
  SvgCanvas svg(100, 100, "dots", "t");
  svg.Dots({{10.0, 10.0}, {10.2, 10.1}, {10.0, 10.0}, {50.0, 50.0}, {NAN, 3.0}}, 2.0, "#000");
  const std::string out = svg.Finish();
  EXPECT_EQ(Count(out, "h0"), 2u) << out;
  EXPECT_TRUE(Contains(out, "stroke-linecap=\"round\""));
}

TEST(SvgNumber, RoundsToATenthWithoutTrailingZero) {
  EXPECT_EQ(SvgNumber(12.0), "12");
  EXPECT_EQ(SvgNumber(12.04), "12");
  EXPECT_EQ(SvgNumber(12.06), "12.1");
  EXPECT_EQ(SvgNumber(-0.01), "0");
  EXPECT_EQ(SvgNumber(INFINITY), "0");
}

TEST(SvgNumber, KeepsTheDecimalsAskedForWithoutTrailingZeros) {
  EXPECT_EQ(SvgNumber(12.34567, 3), "12.346");
  EXPECT_EQ(SvgNumber(12.5, 3), "12.5");
  EXPECT_EQ(SvgNumber(-0.0004, 3), "0");
  EXPECT_EQ(SvgNumber(7.0, 0), "7");
}

// ---- plot frames and labels --------------------------------------------------------------------

TEST(MapFrame, FitsTheBoxAtOneScaleCentredWithYUp) {
  Box box;
  box.Extend({0.0, 0.0});
  box.Extend({10.0, 5.0});
  const MapFrame frame(box, 0, 0, 200, 200);  // limited by x: 20 px/m
  EXPECT_DOUBLE_EQ(frame.pixels_per_m(), 20.0);
  const Eigen::Vector2d low_left = frame.ToPixel({0.0, 0.0});
  const Eigen::Vector2d high_right = frame.ToPixel({10.0, 5.0});
  EXPECT_DOUBLE_EQ(low_left.x(), 0.0);
  EXPECT_DOUBLE_EQ(high_right.x(), 200.0);
  EXPECT_DOUBLE_EQ(low_left.y(), 150.0);  // centred: 50 px free above and below
  EXPECT_DOUBLE_EQ(high_right.y(), 50.0);
  EXPECT_THROW(MapFrame(Box{}, 0, 0, 10, 10), std::invalid_argument);
}

TEST(Box, CentralBoxLeavesOutStrayPointsAndPaddingKeepsAMinimumSize) {
  std::vector<Eigen::Vector2d> points;
  for (int i = 0; i <= 100; ++i) points.emplace_back(0.01 * i, 0.02 * i);
  points.emplace_back(500.0, -500.0);  // one stray far return
  const Box central = CentralBox(points, 0.02);
  EXPECT_LE(central.max.x(), 1.0);
  EXPECT_GE(central.min.y(), 0.0);
  const Box padded = central.Padded(0.0, 4.0);
  EXPECT_NEAR(padded.max.x() - padded.min.x(), 4.0, 1e-12);
  EXPECT_TRUE(CentralBox({}, 0.02).empty());
}

TEST(NiceTicks, AreRoundAndCoverTheRange) {
  EXPECT_EQ(NiceTicks(0.0, 27.0, 4), (std::vector<double>{0, 10, 20}));
  EXPECT_EQ(NiceTicks(0.0, 1.0, 4), (std::vector<double>{0, 0.2, 0.4, 0.6, 0.8, 1.0}));
  EXPECT_DOUBLE_EQ(NiceLengthBelow(13.0), 10.0);
  EXPECT_DOUBLE_EQ(NiceLengthBelow(0.3), 0.2);
  EXPECT_DOUBLE_EQ(NiceLengthBelow(7.5), 5.0);
  EXPECT_THROW(NiceLengthBelow(0.0), std::invalid_argument);
}

TEST(LabelPlacer, LabelsAroundOneAnchorNeverOverlapAndAreDroppedWhenNoRoomIsLeft) {
  LabelPlacer placer(0, 0, 200, 120);
  struct Placed {
    double x0, y0, x1, y1;
  };
  std::vector<Placed> placed;
  int dropped = 0;
  for (int i = 0; i < 40; ++i) {
    const std::string text = "odometry+" + std::to_string(i) + "deg";
    const auto at = placer.Place({100, 60}, text, 11.0);
    if (!at) {
      ++dropped;
      continue;
    }
    const Placed p{at->x(), at->y() - 0.8 * 11.0, at->x() + EstimateTextWidth(text, 11.0),
                   at->y() + 0.2 * 11.0};
    EXPECT_GE(p.x0, 0.0);
    EXPECT_LE(p.x1, 200.0);
    for (const Placed& q : placed)
      EXPECT_FALSE(p.x0 < q.x1 - 1e-9 && q.x0 < p.x1 - 1e-9 && p.y0 < q.y1 - 1e-9 &&
                   q.y0 < p.y1 - 1e-9)
          << "label " << i << " overlaps another";
    placed.push_back(p);
  }
  EXPECT_GE(placed.size(), 5u);
  EXPECT_GT(dropped, 0);
}

TEST(LabelPlacer, WithOneRingALabelStaysBesideItsAnchorOrIsLeftOut) {
  LabelPlacer placer(0, 0, 200, 120, 1);
  int placed = 0;
  for (int i = 0; i < 20; ++i)
    if (const auto at = placer.Place({100, 60}, std::to_string(i), 10.0)) {
      ++placed;
      EXPECT_LT((*at - Eigen::Vector2d(100, 60)).norm(), 4.0 + 10.0 + 3 * 5.8) << i;
    }
  EXPECT_EQ(placed, 4);  // right, left, above, below; the diagonals overlap those
}

// ---- iterations.jsonl ---------------------------------------------------------------------------

LikelihoodTestResult MakeTest(std::vector<int> histogram, int valid_pairs, double ev_m) {
  LikelihoodTestResult t;
  t.histogram = std::move(histogram);
  t.valid_pairs = valid_pairs;
  for (const int c : t.histogram) t.match_pairs += c;
  t.expect_value_m = ev_m;
  t.dispersion_m2 = ev_m * ev_m * 1.5;
  return t;
}

// A localised iteration as the session records it: two candidates (the second invalid by rule
// 1), the first chosen and refined; `valid` false makes both invalid.
IterationRecord Localised(std::size_t index, bool valid, const std::string& label = "p0") {
  IterationRecord r;
  r.index = index;
  r.timestamp_s = 10.0 + index;
  r.origin = "walk.seq.jsonl:" + std::to_string(index + 2);
  r.prediction = {1.0 + 0.1 * index, 2.0, 0.1};
  RankedCandidate a;
  a.candidate = {r.prediction, label};
  a.T_world_robot = r.prediction;
  a.T_world_laser = r.prediction;
  a.test = MakeTest({5, 9, 4, 2, 0, 0, 0, 0, 0, 3}, 30, 0.025);
  a.distance.expect_value_m = 0.02;
  a.cost = 0.04;
  a.verdict = valid ? Verdict::kValid : Verdict::kHighExpectValue;
  a.rank = valid ? 0 : -1;
  RankedCandidate b = a;
  b.candidate = {Pose2D{1.0 + 0.1 * index, 2.0, 0.2}, "p1"};
  b.T_world_robot = b.T_world_laser = b.candidate.T_world_robot;
  b.test = MakeTest({0, 1, 0, 0, 0, 0, 0, 0, 1, 6}, 30, 0.09);
  b.verdict = Verdict::kLowMatchRatio;
  b.rank = -1;
  LocalisationResult localisation;
  localisation.evaluated = {a, b};
  localisation.best_evaluated = valid ? 0 : -1;
  if (!valid) localisation.problems = {"no candidate passed the validation rules"};
  RefinementResult refinement;
  refinement.T_world_laser = {r.prediction.x_m + 0.01, 2.0, 0.1};
  refinement.converged = true;
  refinement.iterations = 3;
  refinement.test_before = a.test;
  refinement.test_after = MakeTest({12, 6, 2, 0, 0, 0, 0, 0, 0, 1}, 30, 0.012);
  RankedCandidate refined = a;
  refined.from = 0;
  refined.refinement = refinement;
  refined.T_world_robot = refined.T_world_laser = refinement.T_world_laser;
  refined.test = refinement.test_after;
  localisation.refined = {refined};
  localisation.best_refined = valid ? 0 : -1;
  localisation.kept = 0;
  r.localisation = localisation;
  r.T_world_robot = valid ? refinement.T_world_laser : r.prediction;
  r.verdict = valid ? Verdict::kValid : Verdict::kHighExpectValue;
  r.validated = valid;
  r.map_points = 100 + index;
  return r;
}

IterationRecord Skipped(std::size_t index) {
  IterationRecord r;
  r.index = index;
  r.timestamp_s = 10.0 + index;
  r.skipped = true;
  r.T_world_robot = r.prediction = {1.0, 2.0, 0.1};
  return r;
}

class ReportTest : public testing::TemporaryDirTest {
 protected:
  // Writes iterations.jsonl as the session does, and returns its path.
  std::string WriteRecords(const std::vector<IterationRecord>& records) const {
    std::string text;
    for (const IterationRecord& r : records) text += ToJson(r).dump() + "\n";
    return Write("iterations.jsonl", text);
  }
  static ReportOptions Everything() {
    ReportOptions options;
    options.selection.first = 100;
    options.selection.flagged = 100;
    return options;
  }
};

TEST_F(ReportTest, RecordsWrittenForTheRunFolderReadBackFieldForField) {
  const std::string path = WriteRecords({Localised(0, true), Skipped(1), Localised(2, false)});
  const IterationRows read = ReadIterationRows(path);
  ASSERT_EQ(read.rows.size(), 3u);
  EXPECT_FALSE(read.truncated_last_line);
  const IterationRow& first = read.rows[0];
  EXPECT_EQ(first.index, 0u);
  EXPECT_EQ(first.origin, "walk.seq.jsonl:2");
  EXPECT_STREQ(first.status(), "validated");
  ASSERT_EQ(first.candidates.size(), 2u);
  EXPECT_EQ(first.candidates[0].label, "p0");
  EXPECT_EQ(first.candidates[0].test.match_pairs, 23);
  EXPECT_EQ(first.candidates[0].test.histogram, (std::vector<int>{5, 9, 4, 2, 0, 0, 0, 0, 0, 3}));
  EXPECT_NEAR(first.candidates[0].distance_expect_value_m.value(), 0.02, 1e-12);
  EXPECT_FALSE(first.candidates[1].valid);
  EXPECT_EQ(first.candidates[1].reason, "rule 1: match ratio too low");
  EXPECT_EQ(first.chosen, "p0");
  ASSERT_TRUE(first.refinement.has_value());
  EXPECT_EQ(first.refinement->after.histogram[0], 12);
  EXPECT_NEAR(first.refinement->T_world_laser.x_m, 1.01, 1e-12);
  EXPECT_STREQ(read.rows[1].status(), "skipped");
  EXPECT_TRUE(read.rows[1].candidates.empty());
  EXPECT_STREQ(read.rows[2].status(), "flagged");
  EXPECT_EQ(read.rows[2].reason, "rule 2: expected value too high");
  EXPECT_EQ(read.rows[2].problems.size(), 1u);
}

TEST_F(ReportTest, LostRecoveredAndTheLaserSignatureAreReadBackAndDrawn) {
  IterationRecord lost = Localised(0, false), recovered = Localised(1, true);
  lost.lost = true;
  lost.signature_expect_value_m = lost.max_expect_value_m = 0.1;
  recovered.recovered = true;
  recovered.search_window = SearchWindow{recovered.prediction, 1.2, 0.5};
  recovered.search = WideSearchResult{};
  recovered.signature_expect_value_m = 0.14;
  recovered.max_expect_value_m = 0.1;
  const IterationRows read = ReadIterationRows(WriteRecords({lost, recovered}));
  ASSERT_EQ(read.rows.size(), 2u);
  EXPECT_TRUE(read.rows[0].lost);
  EXPECT_FALSE(read.rows[0].searched);
  EXPECT_TRUE(read.rows[1].recovered);
  EXPECT_TRUE(read.rows[1].searched);
  EXPECT_NEAR(read.rows[1].signature_expect_value_m.value(), 0.14, 1e-12);
  EXPECT_NEAR(read.rows[1].max_expect_value_m.value(), 0.1, 1e-12);
  const std::string svg = MomentSeriesFigure(read.rows, ValidationOptions{}, "m");
  EXPECT_TRUE(Contains(svg, "laser signature")) << svg;
  EXPECT_TRUE(Contains(svg, "#7b4fb0"));
  // Without the field (older run folders) there is no such line.
  IterationRows old = read;
  for (IterationRow& row : old.rows) row.signature_expect_value_m.reset();
  EXPECT_FALSE(Contains(MomentSeriesFigure(old.rows, ValidationOptions{}, "m"), "#7b4fb0"));
}

TEST_F(ReportTest, ALineThatIsNotJsonIsReportedWithFileAndLine) {
  const std::string good = ToJson(Localised(0, true)).dump();
  const std::string path = Write("iterations.jsonl", good + "\n{\"index\": 1, oops}\n" + good);
  try {
    ReadIterationRows(path);
    FAIL() << "a malformed line was accepted";
  } catch (const ParseError& e) {
    EXPECT_EQ(e.line(), 2u);
    EXPECT_TRUE(Contains(e.what(), path + ":2:")) << e.what();
    EXPECT_TRUE(Contains(e.what(), "expected one JSON object per line")) << e.what();
  }
}

TEST_F(ReportTest, ANumberBeyondADoubleIsReportedWithFileAndLine) {
  std::string bad = ToJson(Localised(1, true)).dump();
  const std::string x = "\"x_m\":";
  bad.replace(bad.find(x), x.size(), x + "1e400,\"was_x_m\":");
  const std::string path =
      Write("iterations.jsonl", ToJson(Localised(0, true)).dump() + "\n" + bad + "\n");
  try {
    ReadIterationRows(path);
    FAIL() << "a number beyond a double was read";
  } catch (const ParseError& e) {
    EXPECT_TRUE(Contains(e.what(), path + ":2: expected one JSON object per line")) << e.what();
  }
}

TEST_F(ReportTest, AWholeNumberBeyondWhatItsFieldHoldsIsRefusedNamingTheField) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"map_points", "1e300"},
      {"map_points", "18446744073709551615"},
      {"histogram", "4294967296"},
      {"rank", "2147483648"},
  };
  for (const auto& [field, number] : cases) {
    nlohmann::json record = ToJson(Localised(0, true));
    if (field == "histogram")
      record["candidates"][0]["likelihood_test"]["histogram"][0] = 0;
    else if (field == "rank")
      record["candidates"][0]["rank"] = 0;
    else
      record[field] = 0;
    std::string text = record.dump();
    const std::string zero = field == "histogram" ? "\"histogram\":[0" : "\"" + field + "\":0";
    ASSERT_NE(text.find(zero), std::string::npos) << text;
    text.replace(text.find(zero), zero.size(),
                 field == "histogram" ? "\"histogram\":[" + number : "\"" + field + "\":" + number);
    const std::string path = Write("iterations.jsonl", text + "\n");
    try {
      ReadIterationRows(path);
      ADD_FAILURE() << field << " = " << number << " was read";
    } catch (const ParseError& e) {
      EXPECT_TRUE(Contains(e.what(), field + ": expected a whole number from 0 to") ||
                  Contains(e.what(), field + ": expected a whole number from -2147483648"))
          << e.what();
    }
  }
}

TEST_F(ReportTest, AFieldOfTheWrongTypeIsNamedWithItsPathFileAndLine) {
  nlohmann::json bad = ToJson(Localised(1, true));
  bad["candidates"][1]["likelihood_test"]["histogram"] = "many";
  const std::string path =
      Write("iterations.jsonl", ToJson(Localised(0, true)).dump() + "\n\n" + bad.dump() + "\n");
  try {
    ReadIterationRows(path);
    FAIL() << "a malformed record was accepted";
  } catch (const ParseError& e) {
    EXPECT_EQ(e.line(), 3u);  // blank lines count
    EXPECT_TRUE(Contains(e.what(), "candidates[1].likelihood_test.histogram: expected an array"))
        << e.what();
  }
  nlohmann::json missing = ToJson(Localised(0, true));
  missing.erase("T_world_robot");
  const std::string path2 = Write("missing.jsonl", missing.dump() + "\n");
  EXPECT_THROW(
      {
        try {
          ReadIterationRows(path2);
        } catch (const ParseError& e) {
          EXPECT_TRUE(Contains(e.what(), "missing.jsonl:1: T_world_robot: expected an object"))
              << e.what();
          throw;
        }
      },
      ParseError);
}

TEST_F(ReportTest, ALastLineCutShortIsLeftOutAndSaid) {
  const std::string good = ToJson(Localised(0, true)).dump();
  const std::string path = Write("iterations.jsonl", good + "\n" + good.substr(0, 40));
  const IterationRows read = ReadIterationRows(path);
  EXPECT_EQ(read.rows.size(), 1u);
  EXPECT_TRUE(read.truncated_last_line);
  // The same cut line followed by a newline is malformed, not cut short.
  const std::string closed = Write("closed.jsonl", good + "\n" + good.substr(0, 40) + "\n");
  EXPECT_THROW(ReadIterationRows(closed), ParseError);
}

TEST_F(ReportTest, RecordsOutOfOrderAreRefused) {
  const std::string path = WriteRecords({Localised(0, true), Localised(2, true)});
  try {
    ReadIterationRows(path);
    FAIL() << "a gap in the iterations was accepted";
  } catch (const ParseError& e) {
    EXPECT_TRUE(Contains(e.what(), ":2: expected the record of iteration 1")) << e.what();
  }
}

// ---- selection ----------------------------------------------------------------------------------

std::vector<IterationRow> Rows(const std::vector<IterationRecord>& records) {
  std::vector<IterationRow> rows;
  for (const IterationRecord& r : records) rows.push_back(IterationRowFromJson(ToJson(r).dump()));
  return rows;
}

TEST(IterationSelection, UnitesTheFirstEveryKthFlaggedAndNamedIterations) {
  // 0–29 localised, flagged when i % 5 == 4 (4, 9, …, 29); 30–39 skipped.
  std::vector<IterationRecord> records;
  for (std::size_t i = 0; i < 30; ++i) records.push_back(Localised(i, i % 5 != 4));
  for (std::size_t i = 30; i < 40; ++i) records.push_back(Skipped(i));
  const std::vector<IterationRow> rows = Rows(records);
  IterationSelectionOptions options;
  options.first = 2;
  options.every = 10;
  options.flagged = 2;
  options.indices = {35};
  const IterationSelection s = SelectIterations(rows, options);
  EXPECT_EQ(s.indices, (std::vector<std::size_t>{0, 1, 4, 10, 20, 29, 35}));
  EXPECT_TRUE(Contains(s.rule, "the first 2 localised")) << s.rule;
  EXPECT_TRUE(Contains(s.rule, "one in every 10 localised (3)")) << s.rule;
  EXPECT_TRUE(Contains(s.rule, "2 of the 6 flagged")) << s.rule;
  EXPECT_TRUE(Contains(s.rule, "7 of 40 iterations drawn")) << s.rule;

  // every = 0 spreads about `spread` over the localised ones.
  options = {};
  options.first = 0;
  options.flagged = 0;
  options.spread = 6;
  EXPECT_EQ(SelectIterations(rows, options).indices,
            (std::vector<std::size_t>{0, 5, 10, 15, 20, 25}));
}

TEST(IterationSelection, ANamedIterationOutsideTheRunIsRefused) {
  const std::vector<IterationRow> rows = Rows({Localised(0, true), Localised(1, true)});
  IterationSelectionOptions options;
  options.indices = {2};
  EXPECT_THROW(SelectIterations(rows, options), std::invalid_argument);
}

TEST(IterationSelection, ListsAreParsedAndBadPartsNamed) {
  EXPECT_EQ(ParseIterationList("3, 10-12,40"), (std::vector<std::size_t>{3, 10, 11, 12, 40}));
  for (const std::string bad : {"", "x", "3,,4", "12-10", "-4", "1.5", "5-"}) {
    EXPECT_THROW(ParseIterationList(bad), std::invalid_argument) << "'" << bad << "'";
  }
  try {
    ParseIterationList("3,a7");
  } catch (const std::invalid_argument& e) {
    EXPECT_TRUE(Contains(e.what(), "'a7'")) << e.what();
  }
}

// ---- figures ------------------------------------------------------------------------------------

TEST(HistogramFigure, DrawsAColumnPerNonEmptySlotAndLabelsTheLastSlot) {
  const LikelihoodTestResult before = MakeTest({5, 9, 4, 2, 0, 0, 0, 0, 0, 3}, 30, 0.025);
  const LikelihoodTestResult after = MakeTest({12, 6, 2, 0, 0, 0, 0, 0, 0, 1}, 30, 0.012);
  const std::string svg = HistogramFigure(before, &after, 0.01, "h");
  EXPECT_EQ(Count(svg, "<title>before, slot"), 5u);
  EXPECT_EQ(Count(svg, "<title>after, slot"), 4u);
  EXPECT_TRUE(Contains(svg, "<title>before, slot 9: 3 pairs</title>"));
  EXPECT_TRUE(Contains(svg,
                       "\xE2\x89\xA5"
                       "9<"));  // the last slot starts at (NS−1)·Δslot = 9 cm
  EXPECT_TRUE(Contains(svg, "before refinement: MP 23 / NVP 30, EV 2.5 cm"));
  EXPECT_TRUE(Contains(svg, "after refinement: MP 21 / NVP 30, EV 1.2 cm"));
}

TEST(HistogramFigure, NoMatchPairSaysSoInsteadOfDrawingEmptyAxes) {
  const std::string svg = HistogramFigure(MakeTest({0, 0, 0}, 10, 0.0), nullptr, 0.01, "h");
  EXPECT_TRUE(Contains(svg, "no match pairs"));
  EXPECT_FALSE(Contains(svg, "slot 0:"));
}

TEST(IterationMapFigure, CandidateLabelsAreEscapedAndTheChosenOneIsBold) {
  const IterationRow row = Rows({Localised(0, true, kNastyLabel)})[0];
  const std::vector<Eigen::Vector2d> map = {{0.0, 0.0}, {3.0, 3.0}};
  IterationFigureInput input;
  input.row = &row;
  input.map_points = &map;
  for (const IterationView view : {IterationView::kScan, IterationView::kCandidates}) {
    input.view = view;
    const std::string svg = IterationMapFigure(input, "m");
    EXPECT_FALSE(Contains(svg, kNastyLabel));
    EXPECT_TRUE(Contains(svg, "font-weight=\"bold\">" + kNastyEscaped + "</text>")) << svg;
    EXPECT_TRUE(Contains(svg, "scan unavailable"));
  }
}

TEST(IterationMapFigure, TheScanIsDrawnAtTheRefinedPostureElseAtTheKeptOne) {
  const std::vector<IterationRow> rows = Rows({Localised(0, true), Skipped(1)});
  LaserMounting mounting;
  mounting.T_robot_laser = {0.2, 0.0, 0.0};
  const Pose2D refined = ScanDrawnAt(rows[0], mounting);
  EXPECT_NEAR(refined.x_m, 1.01, 1e-12);  // the refinement's T_world_laser, mounting included
  const Pose2D kept = ScanDrawnAt(rows[1], mounting);
  EXPECT_NEAR(kept.x_m, 1.0 + 0.2 * std::cos(0.1), 1e-12);
  EXPECT_NEAR(kept.y_m, 2.0 + 0.2 * std::sin(0.1), 1e-12);
}

TEST(CandidateTable, LabelsAreEscapedAndAllInvalidIsSaid) {
  const IterationRow row = Rows({Localised(0, false, kNastyLabel)})[0];
  const std::string html = CandidateTable(row, "t");
  EXPECT_FALSE(Contains(html, kNastyLabel));
  EXPECT_TRUE(Contains(html, kNastyEscaped));
  EXPECT_TRUE(Contains(html, "No candidate passed the validation rules"));
  EXPECT_EQ(Count(html, "<tr class=\"invalid"), 2u);
}

// ---- whole pages --------------------------------------------------------------------------------

TEST_F(ReportTest, ARunWithAnEmptyMapAndNoValidCandidateRendersWithMessages) {
  WriteRecords({Localised(0, false, kNastyLabel), Skipped(1), Localised(2, false)});
  SavePointMapPcd(PointMap{}, dir_ + "/map.pcd");
  Write("summary.json", nlohmann::json{{"log", dir_ + "/gone.seq.jsonl"},
                                       {"inputs", {{"log", dir_ + "/gone.seq.jsonl"}}}}
                            .dump());
  const ReportResult result = WriteRunReport(dir_, Everything());
  EXPECT_EQ(result.path, dir_ + "/report.html");
  const std::string html = ReadText(result.path);
  EXPECT_EQ(html.size(), result.bytes);
  EXPECT_EQ(result.iterations, 3u);
  EXPECT_EQ(result.drawn, 2u);  // the localised ones; the skipped one is in the table only
  EXPECT_EQ(result.drawn_with_scan, 0u);
  EXPECT_TRUE(Contains(html, "No candidate passed the validation rules"));
  EXPECT_TRUE(Contains(html, "the map is empty"));
  EXPECT_TRUE(Contains(html, "gone.seq.jsonl is not there: the scans are unavailable"));
  EXPECT_TRUE(Contains(html, "scan unavailable"));
  EXPECT_FALSE(Contains(html, kNastyLabel));
  EXPECT_TRUE(Contains(html, kNastyEscaped));
  EXPECT_TRUE(Contains(html, "id=\"iteration-0\""));
  EXPECT_TRUE(Contains(html, "id=\"iteration-2\""));
  EXPECT_FALSE(Contains(html, "id=\"iteration-1\""));
  EXPECT_TRUE(Contains(html, "<a href=\"#iteration-2\">2</a>"));
  // Every figure: trajectory, moments, and per drawn iteration two maps and a histogram.
  EXPECT_EQ(Count(html, "<svg "), 2u + 2u * 3u + Count(html, "<td><svg "));
  EXPECT_EQ(Count(html, "<svg "), Count(html, "</svg>"));
  EXPECT_EQ(html.rfind("<!DOCTYPE html>", 0), 0u);
}

// A run without odometry says so in its summary table: how many scans went without it, how many
// the map was searched for, and how many because the odometry never moved while the ranges did.
TEST_F(ReportTest, TheSummaryTableCountsTheScansLocalisedWithoutOdometry) {
  WriteRecords({Localised(0, true), Localised(1, true)});
  SavePointMapPcd(PointMap{}, dir_ + "/map.pcd");
  Write("summary.json", nlohmann::json{{"localised_without_odometry", 1234},
                                       {"motion_searches", 56},
                                       {"odometry_frozen_scans", 789}}
                            .dump());
  const std::string html = ReadText(WriteRunReport(dir_, Everything()).path);
  EXPECT_TRUE(Contains(html, "<th>scans localised without odometry</th><td>1234</td>")) << html;
  EXPECT_TRUE(Contains(html, "<th>searches over the motion seen lately</th><td>56</td>"));
  EXPECT_TRUE(Contains(
      html, "<th>scans whose odometry had not moved while the ranges did</th><td>789</td>"));
}

// Runs written before E_max had one key kept the session's as session.max_expect_value_m: the
// report reads it as the rule 2 the session applied, without a note.
TEST_F(ReportTest, AnOlderRunsSessionExpectValueLimitIsReadAsValidations) {
  WriteRecords({Localised(0, true)});
  SavePointMapPcd(PointMap{}, dir_ + "/map.pcd");
  Write("summary.json", nlohmann::json{{"config",
                                        {{"session", {{"max_expect_value_m", 0.08}}},
                                         {"validation", {{"max_expect_value_m", 0.05}}}}}}
                            .dump());
  const RunContents contents = ReadRunContents(dir_);
  EXPECT_DOUBLE_EQ(contents.config.validation.max_expect_value_m, 0.08);
  for (const std::string& note : contents.notes)
    EXPECT_FALSE(Contains(note, "configuration")) << note;
}

// With loop closure on, the page has a section of the closures tried and what each corrected;
// a run without closures has none.
TEST_F(ReportTest, ARunWithLoopClosuresHasTheirSectionWithTheirCounts) {
  std::vector<IterationRecord> records;
  for (std::size_t i = 0; i < 4; ++i) records.push_back(Localised(i, true));
  WriteRecords(records);
  const std::string plain = ReadText(WriteRunReport(dir_).path);
  EXPECT_FALSE(Contains(plain, "id=\"closures\""));
  records[2].closure.emplace();
  records[2].closure->old_iteration = 0;
  records[2].closure->reason = "no old node in reach";
  records[3].closure.emplace();
  records[3].closure->old_iteration = 1;
  records[3].closure->accepted = true;
  records[3].closure->reason = "accepted";
  records[3].closure->T_world_robot_matched = records[3].T_world_robot;
  records[3].closure->test = LikelihoodTestResult{};
  records[3].closure->largest_shift_m = 0.02;
  WriteRecords(records);
  const std::string html = ReadText(WriteRunReport(dir_).path);
  EXPECT_TRUE(Contains(html, "<h2 id=\"closures\">Loop closures</h2>"));
  EXPECT_TRUE(Contains(html, "2 closures tried, 1 matched against the old nodes, 1 accepted."));
  EXPECT_TRUE(Contains(html,
                       "scan 3 with scan 1, accepted: 0.0 cm, 0.00°; the graph moved a "
                       "node 2.0 cm"));
}

TEST_F(ReportTest, MissingSummaryAndMapAreSaidAndTheRestRenders) {
  WriteRecords({Localised(0, true), Localised(1, true)});
  const ReportResult result = WriteRunReport(dir_, Everything());
  const std::string html = ReadText(result.path);
  EXPECT_TRUE(Contains(html, "summary.json is missing"));
  EXPECT_TRUE(Contains(html, "map.pcd is missing"));
  EXPECT_TRUE(Contains(html, "the run does not name its sequence"));
  EXPECT_TRUE(Contains(html, "no occupancy grid (map.yaml): `scanloc export-grid "));
  EXPECT_FALSE(Contains(html, "trajectory-zoom"));  // no grid figure without a grid
  EXPECT_EQ(result.drawn, 2u);
  EXPECT_EQ(result.notes.size(), 4u);
}

TEST_F(ReportTest, TheTrajectoryIsDrawnOverTheSessionsGridAPixelPerCellZoomableWithoutScript) {
  const std::string run = testing::MakeClassroomRun(dir_);
  ASSERT_FALSE(run.empty());
  const RunContents contents = ReadRunContents(run);
  ASSERT_TRUE(contents.grid.has_value());
  const OccupancyGridImage& grid = *contents.grid;
  EXPECT_DOUBLE_EQ(grid.resolution_m, 0.05);
  EXPECT_GT(grid.width, 120u);  // the 6.3 m × 7 m classroom
  EXPECT_GT(grid.height, 130u);
  const std::string html = ReadText(WriteRunReport(run).path);
  EXPECT_TRUE(Contains(html, GreyscalePngDataUri(grid.width, grid.height, GridShades(grid))));
  EXPECT_TRUE(Contains(
      html, std::to_string(grid.width) + " × " + std::to_string(grid.height) + " cells of 5.0 cm"));
  for (const char* zoom : {"z1", "z2", "z4", "z8", "z16"})
    EXPECT_TRUE(Contains(html, std::string("class=\"") + zoom + "\"")) << zoom;
  EXPECT_FALSE(Contains(html, "<script"));
  EXPECT_TRUE(Contains(html, "<figure class=\"zoomable\">"));
}

TEST_F(ReportTest, AMalformedIterationsFileFailsWithFileAndLineAndWritesNoPage) {
  Write("iterations.jsonl", ToJson(Localised(0, true)).dump() + "\n[1, 2]\n");
  try {
    WriteRunReport(dir_);
    FAIL() << "a malformed iterations.jsonl was accepted";
  } catch (const ParseError& e) {
    EXPECT_TRUE(Contains(e.what(), "iterations.jsonl:2: ")) << e.what();
  }
  EXPECT_FALSE(std::filesystem::exists(dir_ + "/report.html"));
  EXPECT_THROW(WriteRunReport(dir_ + "/nowhere"), std::runtime_error);
}

TEST_F(ReportTest, AMalformedSummaryIsReportedWithItsLine) {
  WriteRecords({Localised(0, true)});
  Write("summary.json", "{\n  \"log\": \"x\",\n  \"iterations\": ,\n}\n");
  try {
    WriteRunReport(dir_);
    FAIL() << "a malformed summary.json was accepted";
  } catch (const ParseError& e) {
    EXPECT_EQ(e.line(), 3u) << e.what();
    EXPECT_TRUE(Contains(e.what(), "summary.json:3:")) << e.what();
  }
}

// The replay of a real session: every selected iteration gets its scan, the map rebuilt before it
// grows from nothing, lies on the classroom's walls (postures and mounting applied right), and a
// different sequence is recognised as such.
TEST_F(ReportTest, ReplayGivesEachSelectedIterationItsScanAndTheMapBeforeIt) {
  const std::string run = testing::MakeClassroomRun(dir_);
  ASSERT_FALSE(run.empty());
  const RunContents contents = ReadRunContents(run);
  ASSERT_TRUE(contents.notes.empty()) << contents.notes.front();
  ASSERT_EQ(contents.log_path, dir_ + "/walk.seq.jsonl");
  ASSERT_FALSE(contents.line_map.empty());
  const std::vector<IterationRow>& rows = contents.iterations.rows;
  ASSERT_EQ(rows.size(), 24u);

  const LineMap walls = ReadLineMap(testing::kClassroomLines);
  auto distance_to_walls = [&](const Eigen::Vector2d& p) {
    double best = INFINITY;
    for (const Segment& s : walls.segments) {
      const Eigen::Vector2d d = s.b - s.a;
      const double t = std::clamp((p - s.a).dot(d) / d.squaredNorm(), 0.0, 1.0);
      best = std::min(best, (s.a + t * d - p).norm());
    }
    return best;
  };
  PointMap map(contents.config.point_map);
  std::vector<std::size_t> visited, map_sizes;
  const ScanReplayResult replay = ReplayScans(
      contents.log_path, rows, {0, 5, 12, 23}, contents.config.mounting,
      contents.config.session.extension, map,
      [&](const IterationRow& row, const LaserScan& scan, const PointMap& before) {
        visited.push_back(row.index);
        // The map rebuilt by ExtendMap is the session's own, point for point in number.
        if (row.index > 0) {
          EXPECT_EQ(before.live_size(), rows[row.index - 1].map_points) << row.index;
        }
        map_sizes.push_back(before.size());
        EXPECT_EQ(scan.size(), 720u);
        for (std::size_t i = 0; i < before.size(); ++i)
          EXPECT_LT(distance_to_walls(before.point(i)), 0.1) << "iteration " << row.index;
      });
  EXPECT_TRUE(replay.problem.empty()) << replay.problem;
  EXPECT_EQ(visited, (std::vector<std::size_t>{0, 5, 12, 23}));
  EXPECT_EQ(map_sizes.front(), 0u);  // the first scan starts the map
  EXPECT_GT(map_sizes[1], 300u);
  EXPECT_GE(map_sizes[3], map_sizes[2]);
  EXPECT_EQ(replay.scans_read, 24u);

  // The whole page: all drawn iterations with their scans.
  const ReportResult result = WriteRunReport(run);
  EXPECT_EQ(result.drawn_with_scan, result.drawn);
  EXPECT_TRUE(result.notes.empty());
  EXPECT_GE(result.drawn, 3u);

  // Another sequence (another name) is not taken for the run's.
  std::filesystem::copy_file(contents.log_path, dir_ + "/other.seq.jsonl");
  ReportOptions options;
  options.inputs.log_path = dir_ + "/other.seq.jsonl";
  const ReportResult other = WriteRunReport(run, options);
  EXPECT_EQ(other.drawn_with_scan, 0u);
  ASSERT_FALSE(other.notes.empty());
  EXPECT_TRUE(Contains(other.notes.back(), "is it the same sequence?")) << other.notes.back();
}

TEST_F(ReportTest, CommandPrintsThePathAndRefusesIterationsOutsideTheRun) {
  const std::string run = testing::MakeClassroomRun(dir_);
  ASSERT_FALSE(run.empty());
  const testing::CommandResult ok =
      testing::RunScanloc({"report", run, "--iterations", "3,7-8", "--every", "5"}, dir_);
  ASSERT_TRUE(ok.exited && ok.exit_code == 0) << ok;
  EXPECT_TRUE(Contains(ok.out, run + "/report.html\n")) << ok;
  const std::string html = ReadText(run + "/report.html");
  for (const char* id : {"iteration-3", "iteration-7", "iteration-8"})
    EXPECT_TRUE(Contains(html, std::string("id=\"") + id + "\"")) << id;
  EXPECT_TRUE(Contains(html, "3 named"));

  const testing::CommandResult out_of_run =
      testing::RunScanloc({"report", run, "--iterations", "24"}, dir_);
  EXPECT_TRUE(out_of_run.exited) << out_of_run;
  EXPECT_NE(out_of_run.exit_code, 0) << out_of_run;
  EXPECT_TRUE(Contains(out_of_run.err, "iteration 24 is not in the run")) << out_of_run;
  const testing::CommandResult bad_list =
      testing::RunScanloc({"report", run, "--iterations", "3-x"}, dir_);
  EXPECT_NE(bad_list.exit_code, 0) << bad_list;
  EXPECT_TRUE(Contains(bad_list.err, "'3-x'")) << bad_list;
}

}  // namespace
}  // namespace scanloc
