// The iteration record format: what the session writes (ToJson(IterationRecord)) the report reads
// back (IterationRowFromJson) field for field, on records of a real session.

#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "scanloc/io/run_folder.hpp"
#include "scanloc/io/sequence_sources.hpp"
#include "scanloc/report/run_records.hpp"
#include "test_support.hpp"

namespace scanloc {
namespace {

void ExpectPose(const Pose2D& read, const Pose2D& written) {
  EXPECT_DOUBLE_EQ(read.x_m, written.x_m);
  EXPECT_DOUBLE_EQ(read.y_m, written.y_m);
  EXPECT_DOUBLE_EQ(read.yaw_rad, written.yaw_rad);
}

void ExpectTest(const LikelihoodTestResult& read, const LikelihoodTestResult& written) {
  EXPECT_EQ(read.valid_pairs, written.valid_pairs);
  EXPECT_EQ(read.match_pairs, written.match_pairs);
  EXPECT_DOUBLE_EQ(read.expect_value_m, written.expect_value_m);
  EXPECT_DOUBLE_EQ(read.dispersion_m2, written.dispersion_m2);
  EXPECT_EQ(read.histogram, written.histogram);
}

void ExpectCandidates(const IterationRow& row, const LocalisationResult& localisation) {
  ASSERT_EQ(row.candidates.size(), localisation.evaluated.size());
  for (std::size_t i = 0; i < row.candidates.size(); ++i) {
    const CandidateRow& read = row.candidates[i];
    const RankedCandidate& written = localisation.evaluated[i];
    EXPECT_EQ(read.label, written.candidate.label);
    ExpectPose(read.T_world_robot, written.candidate.T_world_robot);
    ExpectPose(read.T_world_laser.value(), written.T_world_laser);
    ExpectTest(read.test, written.test);
    EXPECT_DOUBLE_EQ(read.distance_expect_value_m.value(), written.distance.expect_value_m);
    EXPECT_DOUBLE_EQ(read.cost.value(), written.cost);
    EXPECT_EQ(read.valid, written.verdict == Verdict::kValid);
    EXPECT_EQ(read.reason, ToString(written.verdict));
    EXPECT_EQ(read.rank, written.rank);
  }
  EXPECT_EQ(row.problems, localisation.problems);
}

void ExpectRefinements(const IterationRow& row, const IterationRecord& record) {
  const RankedCandidate* kept = record.Kept();
  ASSERT_EQ(row.refinement.has_value(), kept != nullptr);
  if (!kept) return;
  EXPECT_EQ(row.chosen, kept->candidate.label);
  ExpectPose(row.refinement->T_world_laser, kept->refinement->T_world_laser);
  EXPECT_EQ(row.refinement->converged, kept->refinement->converged);
  EXPECT_EQ(row.refinement->iterations, kept->refinement->iterations);
  ExpectTest(row.refinement->before, kept->refinement->test_before);
  ExpectTest(row.refinement->after, kept->refinement->test_after);
  const std::vector<RankedCandidate>& refined = record.localisation->refined;
  ASSERT_EQ(row.refined_candidates.size(), refined.size());
  for (std::size_t i = 0; i < refined.size(); ++i) {
    EXPECT_EQ(row.refined_candidates[i].candidate, refined[i].candidate.label);
    ExpectPose(row.refined_candidates[i].T_world_laser, refined[i].T_world_laser);
    EXPECT_DOUBLE_EQ(row.refined_candidates[i].cost.value(), refined[i].cost);
    EXPECT_EQ(row.refined_candidates[i].rank, refined[i].rank);
    EXPECT_EQ(row.refined_candidates[i].valid, refined[i].verdict == Verdict::kValid);
  }
}

std::string ClassroomSequence() {
  return std::string(SCANLOC_SOURCE_DIR) + "/datasets/classroom/classroom.seq.jsonl";
}

// A session on the classroom's line map from its first true posture.
Session ClassroomSession(const SequenceFileSource& source) {
  SessionConfig config;
  config.session.initial_pose = {1.126, 3.112, 0.0463};
  return Session(
      config, source.mounting(),
      ReadLineMap(std::string(SCANLOC_SOURCE_DIR) + "/datasets/classroom/classroom.lines"),
      PointMap{});
}

TEST(RecordFormat, WhatTheSessionWritesTheReportReadsBackFieldForField) {
  SequenceFileSource source(ClassroomSequence());
  Session session = ClassroomSession(source);
  Iteration iteration;
  int localised = 0, refined = 0;
  for (int i = 0; i < 12 && source.Next(iteration); ++i) {
    const IterationRecord record = session.Process(iteration);
    const IterationRow row = IterationRowFromJson(ToJson(record).dump());
    SCOPED_TRACE("iteration " + std::to_string(i));
    EXPECT_EQ(row.index, record.index);
    EXPECT_DOUBLE_EQ(row.timestamp_s, record.timestamp_s);
    EXPECT_EQ(row.origin, record.origin);
    EXPECT_EQ(row.skipped, record.skipped);
    EXPECT_EQ(row.first, record.first);
    ExpectPose(row.prediction, record.prediction);
    ExpectPose(row.T_world_robot, record.T_world_robot);
    EXPECT_EQ(row.validated, record.validated);
    EXPECT_EQ(row.reason, ToString(record.verdict));
    EXPECT_EQ(row.inserted, record.inserted);
    EXPECT_EQ(row.map_points, record.map_points);
    EXPECT_NEAR(row.total_ms, 1e3 * record.total_s, 1e-9);
    if (record.localisation) {
      ++localised;
      ExpectCandidates(row, *record.localisation);
    }
    refined += record.Kept() != nullptr;
    ExpectRefinements(row, record);
  }
  EXPECT_GE(localised, 10);  // the records compared carry candidates and refinements
  EXPECT_GE(refined, 10);
}

// Every part a record may carry, on a real localisation: the line written must be what dump()
// writes for the value it parses to (members by key, no space, numbers as dump() formats them).
TEST(RecordFormat, TheLineWrittenIsWhatDumpWritesForItsValueWithEveryPartPresent) {
  SequenceFileSource source(ClassroomSequence());
  Session session = ClassroomSession(source);
  Iteration iteration;
  IterationRecord record;
  for (int i = 0; i < 4 && source.Next(iteration); ++i) record = session.Process(iteration);
  ASSERT_NE(record.Kept(), nullptr);
  record.lost = record.recovered = record.beyond_odometry = record.slide_refused = true;
  record.correction_bound = CorrectionBound{0.25, 0.125};
  record.slide_check = SlideCheck{0.5, 0.75, 0.625};
  record.turn_dispute = TurnDispute{{1.0, 2.0, 0.5}, 0.1, 0.02, -0.08};
  record.outranked_refinement = 0;
  record.state = "tentative";
  record.hypotheses.push_back({});
  record.hypotheses.back().T_world_robot = {1.0, 2.0, 0.5};
  record.discarded = {"(1, 2, 0.5): not validated 2 scans in a row"};
  ClosureAttempt closure;
  closure.reason = "accepted";
  closure.test = record.Kept()->test;
  record.closure = closure;
  record.search_window = SearchWindow{};
  record.search = WideSearchResult{};
  record.search->candidates.resize(2);
  std::string line;
  WriteRecord(record, line);
  const nlohmann::json value = nlohmann::json::parse(line);
  EXPECT_EQ(line, value.dump());
  for (const char* key :
       {"lost", "recovered", "beyond_odometry", "correction_bound_m_rad", "state", "posed",
        "hypotheses", "discarded", "closure", "search", "candidates", "chosen", "refinement",
        "refined_candidates", "turn_disputed_by_closure", "outranked_refinement", "slide_refused",
        "correction_sum_before_after_bound_m"})
    EXPECT_TRUE(value.contains(key)) << key;
  EXPECT_EQ(value["turn_disputed_by_closure"]["T_world_robot_tracked"]["yaw_rad"], 0.5);
  EXPECT_EQ(value["outranked_refinement"], 0);
  EXPECT_TRUE(value["closure"].contains("T_old_robot"));
  EXPECT_EQ(value["search"]["found"], 2);
}

}  // namespace
}  // namespace scanloc
