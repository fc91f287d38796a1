// The chapter's findings (§3.4) reproduced in kind on the simulated environments stored in
// datasets/: the classroom's L-shape, the office's blinds, the factory's MinMatchRatio.

#include <gtest/gtest.h>

#include <random>

#include "environment_fixtures.hpp"
#include "scanloc/evaluation/mode_comparison.hpp"
#include "scanloc/session/localisation.hpp"
#include "scanloc/worlds/environments.hpp"
#include "scanloc/worlds/laser_simulator.hpp"

namespace scanloc {
namespace {

// The Likelihood Test of the candidates as given (`scanloc test`).
LocalisationResult Evaluate(const MapView& map, const LaserScan& scan,
                            const std::vector<Candidate>& candidates, const LaserMounting& mounting,
                            const ScoringOptions& scoring, const ValidationOptions& validation) {
  return Localise(map, scan, candidates, mounting, {scoring, validation, {}}, RefinePolicy::kNone);
}

// Every candidate refined and re-validated (`scanloc refine`).
LocalisationResult RefineAll(const MapView& map, const LaserScan& scan,
                             const std::vector<Candidate>& candidates,
                             const LaserMounting& mounting, const ScoringOptions& scoring,
                             const ValidationOptions& validation) {
  return Localise(map, scan, candidates, mounting, {scoring, validation, {}}, RefinePolicy::kAll);
}

using testing::LoadStoredSequence;
using testing::ReadEnvironmentLines;

// The validation rules of the chapter's trials: its E_max of 0.05 m suits its 0.15° laser, which
// the simulated rooms reproduce (the default 0.1 m is for the 0.5–1° benchmark logs).
ValidationOptions ChapterRules() {
  ValidationOptions rules;
  rules.max_expect_value_m = 0.05;
  return rules;
}

// The line file without the groups whose comment mentions `what`.
LineMap Without(const LineFile& file, const std::string& what) {
  LineMap map;
  for (const SegmentGroup& group : file.groups)
    if (group.comment.find(what) == std::string::npos)
      map.segments.insert(map.segments.end(), group.segments.begin(), group.segments.end());
  return map;
}

// The robot posture turned half a revolution about the classroom's centre: what p3 is to p0 in
// Table 1.
Pose2D MirrorInClassroom(const Pose2D& p) {
  return Pose2D{6.32 - p.x_m, 7.0 - p.y_m, p.yaw_rad + M_PI}.Normalized();
}

struct MirrorOutcome {
  int total = 0;
  int mirror_costlier = 0;  // cost (3.11) above the true posture's
  // Near: within 2 m of the south-west corner, where the mirror posture faces the board at close
  // range. Rejected: by any rule.
  int near = 0, rejected_near = 0, rejected_far = 0;
};

MirrorOutcome TestMirrors(const LineMap& map, const std::vector<LaserScan>& scans,
                          const std::vector<Pose2D>& truth, const LaserMounting& mounting) {
  MirrorOutcome outcome;
  for (std::size_t i = 0; i < scans.size(); ++i) {
    const auto result =
        Evaluate({&map, nullptr}, scans[i], {{truth[i], "p0"}, {MirrorInClassroom(truth[i]), "p3"}},
                 mounting, {}, ChapterRules());
    const bool rejected = result.evaluated[1].verdict != Verdict::kValid;
    const bool near = truth[i].Translation().norm() < 2.0;
    ++outcome.total;
    outcome.mirror_costlier += result.evaluated[1].cost > result.evaluated[0].cost;
    outcome.near += near;
    outcome.rejected_near += rejected && near;
    outcome.rejected_far += rejected && !near;
  }
  return outcome;
}

TEST(ClassroomFinding, TheMirrorImageIsRejectedThanksToTheLShapedBoard) {
  const auto sequence = LoadStoredSequence("classroom");
  std::vector<LaserScan> scans;
  for (const auto& it : sequence.iterations) scans.push_back(it.scan);
  const MirrorOutcome with_board = TestMirrors(ReadEnvironmentLines("classroom", "classroom.lines"),
                                               scans, sequence.truth, sequence.mounting);

  // The same postures in the same room without the board, neither in the world nor in the map.
  const Environment room = MakeClassroom();
  const LineMap world = Without(room.world, "L-shaped"), map = Without(room.map, "L-shaped");
  ASSERT_EQ(map.segments.size(), 4u);
  std::mt19937 rng(11);
  std::vector<LaserScan> scans_without_board;
  for (const Pose2D& truth : sequence.truth)
    scans_without_board.push_back(
        SimulateLaser(world, room.mounting.LaserPose(truth), room.laser, rng));
  const MirrorOutcome without_board =
      TestMirrors(map, scans_without_board, sequence.truth, sequence.mounting);

  // With the board, the mirror image costs more than the true posture everywhere; rule 3
  // (max_cost_ratio 1.5) rejects it where the robot stands near the south-west corner, so that
  // the mirror posture faces the board at close range (measured: 11 of the 12 iterations there);
  // farther away the board fills too little of the view (from the chapter's posture, in the
  // middle of the west side, the mirror costs 1.27 times the truth).
  EXPECT_EQ(with_board.mirror_costlier, with_board.total);
  EXPECT_GE(with_board.near, 8);
  EXPECT_GE(with_board.rejected_near, 0.75 * with_board.near) << "of " << with_board.near;
  EXPECT_EQ(with_board.rejected_far, 0);
  // Without the board only the 2 cm skew of the walls tells the two apart: never rejected.
  EXPECT_EQ(without_board.rejected_near + without_board.rejected_far, 0);
}

// Trial (b) and (c) of §3.4.2 along the office path: p0 at the true posture, p2 moved 0.25 m
// toward the south windows, where the blinds' returns fall on the window plane of the map.
class OfficeFinding : public ::testing::Test {
 protected:
  void SetUp() override {
    sequence_ = LoadStoredSequence("office");
    office_ = ReadEnvironmentLines("office", "office.lines");
    with_blinds_ = office_;
    for (const Segment& s : ReadEnvironmentLines("office", "blinds.lines").segments)
      with_blinds_.segments.push_back(s);
    ASSERT_EQ(with_blinds_.segments.size(), office_.segments.size() + 1);
    scoring_.test.match_threshold_m = 0.4;  // T_Map of the office trials
    // The office trials validated p0 at EV 0.106 (Table 4): E_max was above the chapter's 0.05.
    validation_.max_expect_value_m = 0.15;
  }
  static Pose2D TowardTheWindows(const Pose2D& p, double metres) {
    return {p.x_m - metres, p.y_m, p.yaw_rad};
  }
  testing::StoredSequence sequence_;
  LineMap office_, with_blinds_;
  ScoringOptions scoring_;
  ValidationOptions validation_;
};

TEST_F(OfficeFinding, TheBlindsPullTheShiftedCandidateAheadUntilALineIsAddedForThem) {
  int shifted_first_without = 0, shifted_first_with = 0, truth_valid_with = 0;
  const int total = static_cast<int>(sequence_.iterations.size());
  for (int i = 0; i < total; ++i) {
    const Pose2D truth = sequence_.truth[i];
    const std::vector<Candidate> candidates{{truth, "p0"}, {TowardTheWindows(truth, 0.25), "p2"}};
    const LaserScan& scan = sequence_.iterations[i].scan;
    const auto without =
        Evaluate({&office_, nullptr}, scan, candidates, sequence_.mounting, scoring_, validation_);
    const auto with = Evaluate({&with_blinds_, nullptr}, scan, candidates, sequence_.mounting,
                               scoring_, validation_);
    shifted_first_without += without.best_evaluated == 1;
    shifted_first_with += with.best_evaluated == 1;
    truth_valid_with += with.evaluated[0].verdict == Verdict::kValid;
    if (i == 0) {  // Trial (b)'s posture: the blinds' pairs land in the last slot at p0
      EXPECT_GT(without.evaluated[0].test.expect_value_m,
                2.0 * without.evaluated[1].test.expect_value_m);
      EXPECT_LT(with.evaluated[0].test.expect_value_m, 0.5 * with.evaluated[1].test.expect_value_m);
    }
  }
  EXPECT_GE(shifted_first_without, 0.9 * total) << "of " << total;  // measured: all 83
  EXPECT_EQ(shifted_first_with, 0);
  EXPECT_EQ(truth_valid_with, total);
}

TEST_F(OfficeFinding, WithTheBlindsLineBothCandidatesConvergeToOnePosture) {
  for (const std::size_t i : {0, 20, 40, 60}) {
    SCOPED_TRACE("iteration " + std::to_string(i));
    const Pose2D truth = sequence_.truth[i];
    // Frame Localisation's candidates are a little off: as Table 7, p2 about 0.26 m from p0.
    const Pose2D p0{truth.x_m + 0.01, truth.y_m - 0.01, truth.yaw_rad + 0.005};
    const Pose2D p2{truth.x_m - 0.26, truth.y_m + 0.01, truth.yaw_rad + 0.004};
    const LaserScan& scan = sequence_.iterations[i].scan;
    const auto with = RefineAll({&with_blinds_, nullptr}, scan, {{p0, "p0"}, {p2, "p2"}},
                                sequence_.mounting, scoring_, validation_);
    const Pose2D apart = Between(with.refined[0].T_world_robot, with.refined[1].T_world_robot);
    const Pose2D error = Between(truth, with.refined[0].T_world_robot);
    EXPECT_LT(std::hypot(apart.x_m, apart.y_m), 0.005);  // measured: under 1 mm
    EXPECT_LT(std::abs(apart.yaw_rad), 0.002);
    EXPECT_LT(std::hypot(error.x_m, error.y_m), 0.01);  // measured: under 3 mm

    // Without the line, p0 itself is pulled onto the blinds (Trial b: p0 moved 0.16 m).
    const auto without = RefineAll({&office_, nullptr}, scan, {{p0, "p0"}, {p2, "p2"}},
                                   sequence_.mounting, scoring_, validation_);
    const Pose2D pulled = Between(truth, without.refined[0].T_world_robot);
    EXPECT_GT(std::hypot(pulled.x_m, pulled.y_m), 0.15);  // measured: 0.22–0.24 m
  }
}

TEST_F(OfficeFinding, ASessionOnTheLineMapFollowsTheBlindsUntilTheLineIsAdded) {
  const std::string path = testing::EnvironmentDir("office") + "/office.seq.jsonl";
  const ModeResult without = RunMode(MapMode::kLineMap, path, office_, Config{});
  const ModeResult with = RunMode(MapMode::kLineMap, path, with_blinds_, Config{});
  EXPECT_GT(without.mean_translation_error_m, 0.15);  // measured 0.23 m
  EXPECT_LT(with.mean_translation_error_m, 0.01);     // measured 2 mm
  EXPECT_LT(with.max_translation_error_m, 0.02);      // measured 8 mm
  EXPECT_EQ(with.validated, with.localised);
}

TEST(FactoryFinding, ASessionOnTheLineMapValidatesMoreIterationsAtMinMatchRatioPointTwo) {
  const std::string path = testing::EnvironmentDir("factory") + "/factory.seq.jsonl";
  const LineMap factory = ReadEnvironmentLines("factory", "factory.lines");
  Config relaxed;
  relaxed.validation.min_match_ratio = 0.2;
  const ModeResult at_03 = RunMode(MapMode::kLineMap, path, factory, Config{});
  const ModeResult at_02 = RunMode(MapMode::kLineMap, path, factory, relaxed);
  // Measured: 41 and 62 of 80 validated. The relaxed threshold costs no accuracy.
  EXPECT_GE(at_02.validated, at_03.validated + 0.15 * at_03.iterations);
  EXPECT_LE(at_02.mean_translation_error_m, at_03.mean_translation_error_m + 1e-9);
}

TEST(FactoryFinding, MinMatchRatioPointThreeRejectsGoodPosturesThatPointTwoAccepts) {
  const auto sequence = LoadStoredSequence("factory");
  const LineMap factory = ReadEnvironmentLines("factory", "factory.lines");
  // The default MinMatchRatio 0.3, and the factory's 0.2.
  ValidationOptions strict = ChapterRules(), relaxed = ChapterRules();
  relaxed.min_match_ratio = 0.2;
  int valid_strict = 0, valid_relaxed = 0, good = 0;
  const int total = static_cast<int>(sequence.iterations.size());
  for (int i = 0; i < total; ++i) {
    // The true posture: a good posture by construction.
    const std::vector<Candidate> truth{{sequence.truth[i], "truth"}};
    const LaserScan& scan = sequence.iterations[i].scan;
    const auto s = Evaluate({&factory, nullptr}, scan, truth, sequence.mounting, {}, strict);
    const auto r = Evaluate({&factory, nullptr}, scan, truth, sequence.mounting, {}, relaxed);
    good += s.evaluated[0].test.expect_value_m < strict.max_expect_value_m;
    valid_strict += s.best_evaluated == 0;
    valid_relaxed += r.best_evaluated == 0;
    if (s.best_evaluated != 0 && r.best_evaluated == 0) {
      EXPECT_EQ(s.evaluated[0].verdict, Verdict::kLowMatchRatio) << "iteration " << i;
    }
    if (s.best_evaluated == 0) {
      EXPECT_EQ(r.best_evaluated, 0) << "iteration " << i;
    }
  }
  // Every true posture fits the map closely (rule 2), but machinery and walls beyond the reliable
  // range leave few match pairs: 0.3 validates about half of them (measured 41 of 80; the chapter
  // succeeded in 8 of 19 and 7 of 15 iterations), 0.2 most (measured 62).
  EXPECT_EQ(good, total);
  EXPECT_GE(valid_strict, 0.35 * total);
  EXPECT_LE(valid_strict, 0.65 * total);
  EXPECT_GE(valid_relaxed, valid_strict + 0.2 * total);
}

}  // namespace
}  // namespace scanloc
