#include "scanloc/report/run_records.hpp"

#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "scanloc/common/bounded_line.hpp"
#include "scanloc/common/parse_error.hpp"
#include "scanloc/io/record_keys.hpp"

namespace scanloc {
namespace keys = record_keys;
namespace {

using nlohmann::json;

// A field that is missing or of the wrong type; `path` says where (candidates[2].label).
[[noreturn]] void Fail(const std::string& path, const std::string& expected) {
  throw std::runtime_error(path + ": expected " + expected);
}

std::string Join(const std::string& path, const std::string& key) {
  return path.empty() ? key : path + "." + key;
}

const json& Required(const json& object, const std::string& key, const std::string& path,
                     const std::string& expected) {
  const auto it = object.find(key);
  if (it == object.end() || it->is_null()) Fail(Join(path, key), expected);
  return *it;
}

double Number(const json& value, const std::string& path) {
  if (!value.is_number()) Fail(path, "a number");
  return value.get<double>();
}

double RequiredNumber(const json& object, const std::string& key, const std::string& path) {
  return Number(Required(object, key, path, "a number"), Join(path, key));
}

std::optional<double> OptionalNumber(const json& object, const std::string& key,
                                     const std::string& path) {
  const auto it = object.find(key);
  if (it == object.end() || it->is_null()) return std::nullopt;
  return Number(*it, Join(path, key));
}

constexpr long long kIntMax = std::numeric_limits<int>::max();
constexpr long long kIntMin = std::numeric_limits<int>::min();
constexpr long long kWholeMax = std::numeric_limits<long long>::max();

// A JSON integer within [min, max]: a field written from an int or a size_t. A double, or an
// integer beyond what the field holds, fails (a cast would be undefined or wrap).
long long Whole(const json& value, const std::string& path, long long min, long long max) {
  const std::string expected =
      "a whole number from " + std::to_string(min) + " to " + std::to_string(max);
  if (!value.is_number_integer()) Fail(path, expected);
  if (value.is_number_unsigned() &&
      value.get<unsigned long long>() > static_cast<unsigned long long>(kWholeMax))
    Fail(path, expected);
  const long long whole = value.get<long long>();
  if (whole < min || whole > max) Fail(path, expected);
  return whole;
}

int RequiredInteger(const json& object, const std::string& key, const std::string& path) {
  const json& value = Required(object, key, path, "a whole number");
  return static_cast<int>(Whole(value, Join(path, key), 0, kIntMax));
}

std::optional<long long> OptionalWhole(const json& object, const std::string& key,
                                       const std::string& path, long long min, long long max) {
  const auto it = object.find(key);
  if (it == object.end() || it->is_null()) return std::nullopt;
  return Whole(*it, Join(path, key), min, max);
}

bool RequiredBool(const json& object, const std::string& key, const std::string& path) {
  const json& value = Required(object, key, path, "true or false");
  if (!value.is_boolean()) Fail(Join(path, key), "true or false");
  return value.get<bool>();
}

bool OptionalBool(const json& object, const std::string& key, const std::string& path) {
  const auto it = object.find(key);
  if (it == object.end() || it->is_null()) return false;
  if (!it->is_boolean()) Fail(Join(path, key), "true or false");
  return it->get<bool>();
}

std::string RequiredString(const json& object, const std::string& key, const std::string& path) {
  const json& value = Required(object, key, path, "a string");
  if (!value.is_string()) Fail(Join(path, key), "a string");
  return value.get<std::string>();
}

std::string OptionalString(const json& object, const std::string& key, const std::string& path) {
  const auto it = object.find(key);
  if (it == object.end() || it->is_null()) return "";
  if (!it->is_string()) Fail(Join(path, key), "a string");
  return it->get<std::string>();
}

Pose2D PoseFrom(const json& value, const std::string& path) {
  if (!value.is_object()) Fail(path, "an object with x_m, y_m, yaw_rad");
  return {RequiredNumber(value, keys::kXM, path), RequiredNumber(value, keys::kYM, path),
          RequiredNumber(value, keys::kYawRad, path)};
}

Pose2D RequiredPose(const json& object, const std::string& key, const std::string& path) {
  return PoseFrom(Required(object, key, path, "an object with x_m, y_m, yaw_rad"), Join(path, key));
}

std::optional<Pose2D> OptionalPose(const json& object, const std::string& key,
                                   const std::string& path) {
  const auto it = object.find(key);
  if (it == object.end() || it->is_null()) return std::nullopt;
  return PoseFrom(*it, Join(path, key));
}

const json& RequiredArray(const json& object, const std::string& key, const std::string& path,
                          const std::string& expected) {
  const json& value = Required(object, key, path, expected);
  if (!value.is_array()) Fail(Join(path, key), expected);
  return value;
}

LikelihoodTestResult TestFrom(const json& value, const std::string& path) {
  if (!value.is_object()) Fail(path, "an object with the Likelihood Test's moments");
  LikelihoodTestResult test;
  test.valid_pairs = RequiredInteger(value, keys::kValidPairs, path);
  test.match_pairs = RequiredInteger(value, keys::kMatchPairs, path);
  test.expect_value_m = RequiredNumber(value, keys::kExpectValueM, path);
  test.dispersion_m2 = RequiredNumber(value, keys::kDispersionM2, path);
  const std::string histogram_path = Join(path, keys::kHistogram);
  const json& histogram =
      RequiredArray(value, keys::kHistogram, path, "an array of whole numbers (slot counts)");
  for (const json& count : histogram)
    test.histogram.push_back(static_cast<int>(Whole(count, histogram_path, 0, kIntMax)));
  return test;
}

LikelihoodTestResult RequiredTest(const json& object, const std::string& key,
                                  const std::string& path) {
  return TestFrom(Required(object, key, path, "an object"), Join(path, key));
}

std::optional<double> DistanceExpectValue(const json& object, const std::string& key,
                                          const std::string& path) {
  const auto it = object.find(key);
  if (it == object.end() || it->is_null()) return std::nullopt;
  if (!it->is_object()) Fail(Join(path, key), "an object with the Likelihood Distance");
  return OptionalNumber(*it, keys::kExpectValueM, Join(path, key));
}

// The rules' verdict on a candidate, tested or refined: valid, reason and rank.
template <class Row>
void ReadVerdict(const json& value, const std::string& path, Row& row) {
  row.valid = RequiredBool(value, keys::kValid, path);
  row.reason = OptionalString(value, keys::kReason, path);
  if (const auto rank = OptionalWhole(value, keys::kRank, path, kIntMin, kIntMax))
    row.rank = static_cast<int>(*rank);
}

CandidateRow CandidateFrom(const json& value, const std::string& path) {
  if (!value.is_object()) Fail(path, "an object (a candidate)");
  CandidateRow c;
  c.label = RequiredString(value, keys::kLabel, path);
  c.T_world_robot = RequiredPose(value, keys::kTWorldRobot, path);
  c.T_world_laser = OptionalPose(value, keys::kTWorldLaser, path);
  c.test = RequiredTest(value, keys::kLikelihoodTest, path);
  c.distance_expect_value_m = DistanceExpectValue(value, keys::kLikelihoodDistance, path);
  c.cost = OptionalNumber(value, keys::kCost, path);
  ReadVerdict(value, path, c);
  return c;
}

RefinementRow RefinementFrom(const json& value, const std::string& path) {
  if (!value.is_object()) Fail(path, "an object (the refinement)");
  RefinementRow r;
  r.T_world_laser = RequiredPose(value, keys::kTWorldLaser, path);
  r.converged = OptionalBool(value, keys::kConverged, path);
  if (const auto iterations = OptionalWhole(value, keys::kIterations, path, 0, kIntMax))
    r.iterations = static_cast<int>(*iterations);
  r.before = RequiredTest(value, keys::kLikelihoodTestBefore, path);
  r.after = RequiredTest(value, keys::kLikelihoodTestAfter, path);
  r.distance_expect_value_before_m =
      DistanceExpectValue(value, keys::kLikelihoodDistanceBefore, path);
  r.distance_expect_value_after_m =
      DistanceExpectValue(value, keys::kLikelihoodDistanceAfter, path);
  r.degenerate = OptionalBool(value, keys::kDegenerate, path);
  r.degeneracy = OptionalString(value, keys::kDegeneracy, path);
  r.time_s = OptionalNumber(value, keys::kTimeS, path).value_or(0.0);
  return r;
}

RefinedCandidateRow RefinedCandidateFrom(const json& value, const std::string& path) {
  if (!value.is_object()) Fail(path, "an object (a refined candidate)");
  RefinedCandidateRow r;
  r.candidate = RequiredString(value, keys::kCandidate, path);
  r.T_world_laser = RequiredPose(value, keys::kTWorldLaser, path);
  r.cost = OptionalNumber(value, keys::kCost, path);
  r.expect_value_m = OptionalNumber(value, keys::kExpectValueM, path);
  r.match_ratio = OptionalNumber(value, keys::kMatchRatio, path);
  ReadVerdict(value, path, r);
  return r;
}

std::size_t RequiredCount(const json& object, const std::string& key, const std::string& path) {
  const json& value = Required(object, key, path, "a whole number");
  return static_cast<std::size_t>(Whole(value, Join(path, key), 0, kWholeMax));
}

// The loop closure tried after the record's scan, if any.
std::optional<ClosureRow> ClosureFrom(const json& record) {
  const auto it = record.find(keys::kClosure);
  if (it == record.end()) return std::nullopt;
  if (!it->is_object()) Fail(keys::kClosure, "an object");
  ClosureRow closure;
  closure.accepted = RequiredBool(*it, keys::kAccepted, keys::kClosure);
  closure.reason = OptionalString(*it, keys::kReason, keys::kClosure);
  closure.old_iteration = RequiredCount(*it, keys::kOldIteration, keys::kClosure);
  closure.node = RequiredCount(*it, keys::kNode, keys::kClosure);
  closure.old_node = RequiredCount(*it, keys::kOldNode, keys::kClosure);
  // Only with the refinement's test: older run folders wrote an identity when nothing was refined.
  if (it->contains(keys::kExpectValueM)) {
    closure.T_old_robot = OptionalPose(*it, keys::kTOldRobot, keys::kClosure);
    closure.T_world_robot_matched = OptionalPose(*it, keys::kMatched, keys::kClosure);
  }
  closure.largest_shift_m = OptionalNumber(*it, keys::kLargestShiftM, keys::kClosure);
  return closure;
}

IterationRow RowFrom(const json& record) {
  if (!record.is_object()) Fail("the record", "a JSON object");
  IterationRow row;
  row.index = RequiredCount(record, keys::kIndex, "");
  row.timestamp_s = RequiredNumber(record, keys::kTimestampS, "");
  row.origin = OptionalString(record, keys::kOrigin, "");
  row.skipped = RequiredBool(record, keys::kSkipped, "");
  row.first = OptionalBool(record, keys::kFirst, "");
  row.prediction = RequiredPose(record, keys::kPrediction, "");
  row.T_world_robot = RequiredPose(record, keys::kTWorldRobot, "");
  row.validated = RequiredBool(record, keys::kValidated, "");
  row.reason = OptionalString(record, keys::kReason, "");
  row.inserted = OptionalBool(record, keys::kInserted, "");
  if (const auto points = OptionalWhole(record, keys::kMapPoints, "", 0, kWholeMax))
    row.map_points = static_cast<std::size_t>(*points);
  if (const auto it = record.find(keys::kTimingsMs); it != record.end() && it->is_object()) {
    row.evaluate_ms = OptionalNumber(*it, keys::kEvaluate, keys::kTimingsMs).value_or(0.0);
    row.refine_ms = OptionalNumber(*it, keys::kRefine, keys::kTimingsMs).value_or(0.0);
    row.insert_ms = OptionalNumber(*it, keys::kInsert, keys::kTimingsMs).value_or(0.0);
    row.total_ms = OptionalNumber(*it, keys::kTotal, keys::kTimingsMs).value_or(0.0);
  }
  if (record.contains(keys::kCandidates)) {
    const json& candidates = RequiredArray(record, keys::kCandidates, "", "an array of candidates");
    for (std::size_t i = 0; i < candidates.size(); ++i)
      row.candidates.push_back(
          CandidateFrom(candidates[i], "candidates[" + std::to_string(i) + "]"));
  }
  row.chosen = OptionalString(record, keys::kChosen, "");
  row.max_expect_value_m = OptionalNumber(record, keys::kMaxExpectValueM, "");
  row.signature_expect_value_m = OptionalNumber(record, keys::kSignatureExpectValueM, "");
  row.lost = OptionalBool(record, keys::kLost, "");
  row.recovered = OptionalBool(record, keys::kRecovered, "");
  row.searched = record.contains(keys::kSearch);
  row.state = OptionalString(record, keys::kState, "");
  row.posed = !record.contains(keys::kPosed) || OptionalBool(record, keys::kPosed, "");
  row.closure = ClosureFrom(record);
  if (record.contains(keys::kHypotheses))
    row.hypotheses = RequiredArray(record, keys::kHypotheses, "", "an array of hypotheses").size();
  if (record.contains(keys::kProblems)) {
    for (const json& problem : RequiredArray(record, keys::kProblems, "", "an array of strings")) {
      if (!problem.is_string()) Fail(keys::kProblems, "an array of strings");
      row.problems.push_back(problem.get<std::string>());
    }
  }
  if (const auto it = record.find(keys::kRefinement); it != record.end() && !it->is_null())
    row.refinement = RefinementFrom(*it, keys::kRefinement);
  if (record.contains(keys::kRefinedCandidates)) {
    const json& refined =
        RequiredArray(record, keys::kRefinedCandidates, "", "an array of refined candidates");
    for (std::size_t i = 0; i < refined.size(); ++i)
      row.refined_candidates.push_back(
          RefinedCandidateFrom(refined[i], "refined_candidates[" + std::to_string(i) + "]"));
  }
  return row;
}

}  // namespace

const char* IterationRow::status() const {
  if (first) return "first";
  if (skipped) return "skipped";
  return validated ? "validated" : "flagged";
}

std::optional<std::size_t> IterationRow::closed_with() const {
  if (!closure || !closure->accepted) return std::nullopt;
  return closure->old_iteration;
}

const CandidateRow* IterationRow::chosen_candidate() const {
  for (const CandidateRow& c : candidates)
    if (c.label == chosen) return &c;
  return nullptr;
}

IterationRow IterationRowFromJson(const std::string& json_text) {
  json record;
  try {
    record = json::parse(json_text);
  } catch (const json::exception& e) {  // a syntax error, or a number beyond a double
    throw std::runtime_error(std::string("expected one JSON object per line: ") + e.what());
  }
  return RowFrom(record);
}

IterationRows ReadIterationRows(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open " + path);
  IterationRows result;
  std::string text;
  for (std::size_t line = 1; ReadBoundedLine(in, text, path, line); ++line) {
    if (text.find_first_not_of(" \t\r") == std::string::npos) continue;
    const bool last_without_newline = in.eof();
    IterationRow row;
    try {
      row = IterationRowFromJson(text);
    } catch (const std::runtime_error& e) {
      if (last_without_newline && !json::accept(text)) {
        result.truncated_last_line = true;
        break;
      }
      throw ParseError(path, line, e.what());
    }
    if (row.index != result.rows.size())
      throw ParseError(path, line,
                       "expected the record of iteration " + std::to_string(result.rows.size()) +
                           " (one record per iteration, in order), got index " +
                           std::to_string(row.index));
    result.rows.push_back(std::move(row));
  }
  if (in.bad()) throw std::runtime_error("error while reading " + path);
  return result;
}

}  // namespace scanloc
