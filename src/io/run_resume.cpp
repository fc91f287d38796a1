#include "scanloc/io/run_resume.hpp"

#include <filesystem>
#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "scanloc/common/bounded_line.hpp"
#include "scanloc/common/parse_error.hpp"
#include "scanloc/io/record_keys.hpp"

namespace scanloc {
namespace keys = record_keys;
namespace {

using nlohmann::json;

Pose2D PoseFrom(const json& pose) {
  return {pose.at(keys::kXM).get<double>(), pose.at(keys::kYM).get<double>(),
          pose.at(keys::kYawRad).get<double>()};
}

LikelihoodTestResult TestFrom(const json& test) {
  LikelihoodTestResult result;
  result.valid_pairs = test.at(keys::kValidPairs).get<int>();
  result.match_pairs = test.at(keys::kMatchPairs).get<int>();
  result.expect_value_m = test.at(keys::kExpectValueM).get<double>();
  result.dispersion_m2 = test.at(keys::kDispersionM2).get<double>();
  result.histogram = test.at(keys::kHistogram).get<std::vector<int>>();
  return result;
}

Eigen::Matrix3d CovarianceFrom(const json& rows) {
  if (!rows.is_array() || rows.size() != 3) throw std::invalid_argument("covariance: 3 rows");
  Eigen::Matrix3d covariance;
  for (int i = 0; i < 3; ++i) {
    if (!rows[i].is_array() || rows[i].size() != 3)
      throw std::invalid_argument("covariance: 3 columns");
    for (int j = 0; j < 3; ++j) covariance(i, j) = rows[i][j].get<double>();
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
    r.index = record.at(keys::kIndex).get<std::size_t>();
    r.timestamp_s = record.at(keys::kTimestampS).get<double>();
    r.skipped = record.at(keys::kSkipped).get<bool>();
    r.first = record.at(keys::kFirst).get<bool>();
    r.localised = record.contains(keys::kCandidates);
    r.T_world_robot = PoseFrom(record.at(keys::kTWorldRobot));
    r.validated = record.at(keys::kValidated).get<bool>();
    r.verdict = VerdictFrom(record.at(keys::kReason).get<std::string>());
    if (r.localised)
      r.signature_expect_value_m = record.at(keys::kSignatureExpectValueM).get<double>();
    r.lost = FlagOr(record, keys::kLost, false);
    r.recovered = FlagOr(record, keys::kRecovered, false);
    r.inserted = record.at(keys::kInserted).get<bool>();
    r.carved = record.at(keys::kCarved).get<std::size_t>();
    r.map_points = record.at(keys::kMapPoints).get<std::size_t>();
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
