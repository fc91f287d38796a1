#include "scanloc/io/run_resume.hpp"

#include <cstdint>
#include <filesystem>
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

// Numbers as the record writer wrote them: integers where it wrote integers (a float converted to
// an integer type out of its range would be undefined behaviour).
std::int64_t Integer(const json& value, const char* key, std::int64_t min, std::int64_t max) {
  if (!value.is_number_integer())
    throw std::invalid_argument(std::string(key) + ": expected an integer");
  if (value.is_number_unsigned() && value.get<std::uint64_t>() > static_cast<std::uint64_t>(max))
    throw std::invalid_argument(std::string(key) + ": out of range");
  const std::int64_t v = value.is_number_unsigned()
                             ? static_cast<std::int64_t>(value.get<std::uint64_t>())
                             : value.get<std::int64_t>();
  if (v < min || v > max) throw std::invalid_argument(std::string(key) + ": out of range");
  return v;
}

int Int(const json& object, const char* key) {
  return static_cast<int>(Integer(object.at(key), key, 0, std::numeric_limits<int>::max()));
}

std::size_t Count(const json& object, const char* key) {
  return static_cast<std::size_t>(
      Integer(object.at(key), key, 0, std::numeric_limits<std::int64_t>::max()));
}

double Real(const json& object, const char* key) {
  const json& value = object.at(key);
  if (!value.is_number()) throw std::invalid_argument(std::string(key) + ": expected a number");
  return value.get<double>();
}

Pose2D PoseFrom(const json& pose) {
  return {Real(pose, keys::kXM), Real(pose, keys::kYM), Real(pose, keys::kYawRad)};
}

LikelihoodTestResult TestFrom(const json& test) {
  LikelihoodTestResult result;
  result.valid_pairs = Int(test, keys::kValidPairs);
  result.match_pairs = Int(test, keys::kMatchPairs);
  result.expect_value_m = Real(test, keys::kExpectValueM);
  result.dispersion_m2 = Real(test, keys::kDispersionM2);
  const json& histogram = test.at(keys::kHistogram);
  if (!histogram.is_array()) throw std::invalid_argument("histogram: expected an array");
  for (const json& slot : histogram)
    result.histogram.push_back(
        static_cast<int>(Integer(slot, keys::kHistogram, 0, std::numeric_limits<int>::max())));
  return result;
}

Eigen::Matrix3d CovarianceFrom(const json& rows) {
  if (!rows.is_array() || rows.size() != 3) throw std::invalid_argument("covariance: 3 rows");
  Eigen::Matrix3d covariance;
  for (int i = 0; i < 3; ++i) {
    if (!rows[i].is_array() || rows[i].size() != 3)
      throw std::invalid_argument("covariance: 3 columns");
    for (int j = 0; j < 3; ++j) {
      if (!rows[i][j].is_number()) throw std::invalid_argument("covariance: expected numbers");
      covariance(i, j) = rows[i][j].get<double>();
    }
  }
  return covariance;
}

Verdict VerdictFrom(const std::string& reason) {
  for (const Verdict v : {Verdict::kValid, Verdict::kNoValidPairs, Verdict::kLowMatchRatio,
                          Verdict::kHighExpectValue, Verdict::kHighCost})
    if (reason == ToString(v)) return v;
  throw std::invalid_argument("reason: unknown verdict '" + reason + "'");
}

bool FlagOr(const json& record, const char* key, bool otherwise) {
  return record.contains(key) ? record.at(key).get<bool>() : otherwise;
}

// The kept refinement, closure and search parts of a record.
void AddOptionalParts(const json& record, RecordedIteration& r) {
  if (record.contains(keys::kRefinement)) {
    const json& refinement = record.at(keys::kRefinement);
    r.kept_test = TestFrom(refinement.at(keys::kLikelihoodTestAfter));
    if (refinement.contains(keys::kCovariance))
      r.kept_covariance = CovarianceFrom(refinement.at(keys::kCovariance));
  }
  if (record.contains(keys::kClosure)) {
    const json& closure = record.at(keys::kClosure);
    r.closure_tried = true;
    r.closure_accepted = closure.at(keys::kAccepted).get<bool>();
    r.closure_rendered = closure.at(keys::kRendered).get<bool>();
  }
  r.searched = record.contains(keys::kSearch);
}

}  // namespace

RecordedIteration RecordedFromJson(const json& record) {
  try {
    RecordedIteration r;
    r.index = Count(record, keys::kIndex);
    r.timestamp_s = Real(record, keys::kTimestampS);
    r.skipped = record.at(keys::kSkipped).get<bool>();
    r.first = record.at(keys::kFirst).get<bool>();
    r.localised = record.contains(keys::kCandidates);
    r.T_world_robot = PoseFrom(record.at(keys::kTWorldRobot));
    r.validated = record.at(keys::kValidated).get<bool>();
    r.verdict = VerdictFrom(record.at(keys::kReason).get<std::string>());
    if (r.localised) r.signature_expect_value_m = Real(record, keys::kSignatureExpectValueM);
    if (record.contains(keys::kBeyondOdometry))
      r.refused = PoseFrom(record.at(keys::kBeyondOdometry));
    if (record.contains(keys::kSlideRefused))
      r.slide_refused = PoseFrom(record.at(keys::kSlideRefused));
    if (record.contains(keys::kTurnDisputed))
      r.disputed = PoseFrom(record.at(keys::kTurnDisputed).at(keys::kTracked));
    if (record.contains(keys::kOutrankedRefinement))
      r.outranked_refinement = record.at(keys::kOutrankedRefinement).get<int>();
    r.lost = FlagOr(record, keys::kLost, false);
    r.recovered = FlagOr(record, keys::kRecovered, false);
    r.inserted = record.at(keys::kInserted).get<bool>();
    r.new_ground = FlagOr(record, keys::kNewGround, false);
    r.carved = Count(record, keys::kCarved);
    r.map_points = Count(record, keys::kMapPoints);
    AddOptionalParts(record, r);
    return r;
  } catch (const json::exception& e) {
    throw std::invalid_argument(std::string("not an iteration record: ") + e.what());
  }
}

RecordedRun ReadRecordsToResume(const std::string& path) {
  std::error_code error;
  const std::uintmax_t size = std::filesystem::file_size(path, error);
  std::ifstream in(path, std::ios::binary);
  if (error || !in) throw std::runtime_error("cannot read " + path + " to resume the run");
  RecordedRun run;
  std::string line;
  for (std::size_t number = 1; ReadBoundedLine(in, line, path, number); ++number) {
    if (run.complete_bytes + line.size() + 1 > size) {  // no newline: cut off while written
      run.partial_line = true;
      break;
    }
    try {
      run.iterations.push_back(RecordedFromJson(json::parse(line)));
    } catch (const std::exception& e) {
      throw ParseError(path, number, std::string("expected an iteration record: ") + e.what());
    }
    if (run.iterations.back().index != number - 1)
      throw ParseError(path, number,
                       "expected the record of iteration " + std::to_string(number - 1) +
                           ", found iteration " + std::to_string(run.iterations.back().index));
    run.complete_bytes += line.size() + 1;
  }
  return run;
}

}  // namespace scanloc
