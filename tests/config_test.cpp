#include "scanloc/config/config.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <optional>
#include <stdexcept>
#include <string>

#include "test_support.hpp"

namespace scanloc {
namespace {

using nlohmann::json;

// The message of the exception ApplyJson throws for `patch`, or "" when it accepts it.
std::string ApplyJsonError(const json& patch) {
  Config config;
  try {
    ApplyJson(patch, config);
  } catch (const std::runtime_error& error) {
    return error.what();
  }
  return "";
}

// The message of the exception ApplyJson followed by Validate throws, or "" when both accept.
std::string ApplyAndValidateError(const json& patch) {
  Config config;
  try {
    ApplyJson(patch, config);
    config.Validate();
  } catch (const std::exception& error) {
    return error.what();
  }
  return "";
}

using testing::Contains;

class ConfigFileTest : public testing::TemporaryDirTest {
 protected:
  using TemporaryDirTest::Write;
  std::string Write(const std::string& content) const { return Write("config.json", content); }
  // The message LoadConfig throws for a file with `content`, or "" when it loads.
  std::string LoadError(const std::string& content) const {
    try {
      LoadConfig(Write(content));
    } catch (const std::runtime_error& error) {
      return error.what();
    }
    return "";
  }
};

TEST(Config, DefaultsAreTheChaptersValuesExceptEmax) {
  const Config config;
  EXPECT_EQ(config.scoring.test.slot_count, 20);                    // NS
  EXPECT_DOUBLE_EQ(config.scoring.test.slot_width_m, 0.01);         // Δslot
  EXPECT_DOUBLE_EQ(config.scoring.test.match_threshold_m, 0.5);     // T_Map
  EXPECT_NEAR(config.scoring.test.LastSlotDistance(), 0.3, 1e-15);  // Δmax = 3/2·NS·Δslot
  EXPECT_DOUBLE_EQ(config.validation.min_match_ratio, 0.3);         // MinMatchRatio
  // E_max: the chapter's 0.05 m suits its 0.15° laser, 0.1 m the 0.5–1° benchmark logs.
  EXPECT_DOUBLE_EQ(config.validation.max_expect_value_m, 0.1);
  EXPECT_NO_THROW(config.Validate());
}

TEST(Config, LastSlotDistanceFollowsSlotCountAndWidthUnlessSet) {
  Config config;
  ApplyJson(json{{"likelihood_test", {{"slot_count", 30}, {"slot_width_m", 0.02}}}}, config);
  EXPECT_NEAR(config.scoring.test.LastSlotDistance(), 1.5 * 30 * 0.02, 1e-15);
  ApplyJson(json{{"likelihood_test", {{"last_slot_distance_m", 0.7}}}}, config);
  EXPECT_DOUBLE_EQ(config.scoring.test.LastSlotDistance(), 0.7);
}

TEST(Config, ApplyJsonOverridesOnlyTheGivenKeys) {
  Config config;
  ApplyJson(json::parse(R"({"likelihood_test": {"match_threshold_m": 0.4},
                            "validation": {"min_match_ratio": 0.2},
                            "likelihood_distance": {"kernel": "huber"},
                            "mounting": {"x_m": 0.25}})"),
            config);
  EXPECT_DOUBLE_EQ(config.scoring.test.match_threshold_m, 0.4);
  EXPECT_DOUBLE_EQ(config.validation.min_match_ratio, 0.2);
  EXPECT_EQ(config.scoring.distance.kernel, RobustKernel::kHuber);
  EXPECT_DOUBLE_EQ(config.mounting.T_robot_laser.x_m, 0.25);
  // Everything else keeps its default.
  const Config defaults;
  EXPECT_EQ(config.scoring.test.slot_count, defaults.scoring.test.slot_count);
  EXPECT_DOUBLE_EQ(config.scoring.test.slot_width_m, defaults.scoring.test.slot_width_m);
  EXPECT_DOUBLE_EQ(config.validation.max_expect_value_m, defaults.validation.max_expect_value_m);
  EXPECT_DOUBLE_EQ(config.scoring.distance.scale_m, defaults.scoring.distance.scale_m);
  EXPECT_DOUBLE_EQ(config.mounting.T_robot_laser.y_m, 0.0);
  EXPECT_DOUBLE_EQ(config.line_sampling_m, defaults.line_sampling_m);
}

TEST(Config, EmptyObjectChangesNothing) {
  Config config;
  ApplyJson(json::object(), config);
  EXPECT_EQ(ToJson(config), ToJson(Config{}));
}

TEST(Config, UnknownKeysAreRefusedWithTheirPath) {
  const std::string nested = ApplyJsonError(json{{"validation", {{"nonsense", 1}}}});
  EXPECT_TRUE(Contains(nested, "config.validation")) << nested;
  EXPECT_TRUE(Contains(nested, "'nonsense'")) << nested;

  const std::string top = ApplyJsonError(json{{"likelihood_tset", {{"slot_count", 20}}}});
  EXPECT_TRUE(Contains(top, "config")) << top;
  EXPECT_TRUE(Contains(top, "'likelihood_tset'")) << top;
}

// A dotted key would match a declared path, yet JSON nests sections as objects: refused, not
// ignored.
TEST(Config, DottedKeyIsRefusedRatherThanIgnored) {
  const std::string message = ApplyJsonError(json{{"likelihood_test.slot_count", 30}});
  EXPECT_TRUE(Contains(message, "'likelihood_test.slot_count'")) << message;
}

TEST(Config, WrongTypesAreRefusedWithTheKeyPath) {
  const std::string count = ApplyJsonError(json{{"likelihood_test", {{"slot_count", "twenty"}}}});
  EXPECT_TRUE(Contains(count, "config.likelihood_test.slot_count")) << count;
  EXPECT_TRUE(Contains(count, "whole number")) << count;

  const std::string width = ApplyJsonError(json{{"likelihood_test", {{"slot_width_m", "wide"}}}});
  EXPECT_TRUE(Contains(width, "config.likelihood_test.slot_width_m")) << width;
  EXPECT_TRUE(Contains(width, "number")) << width;

  const std::string boolean = ApplyJsonError(json{{"validation", {{"alpha_m", true}}}});
  EXPECT_TRUE(Contains(boolean, "config.validation.alpha_m")) << boolean;

  const std::string section = ApplyJsonError(json{{"validation", 0.3}});
  EXPECT_TRUE(Contains(section, "config.validation")) << section;
  EXPECT_TRUE(Contains(section, "object")) << section;

  EXPECT_FALSE(ApplyJsonError(json::array()).empty());
}

TEST(Config, UnknownKernelNameIsRefusedWithTheKeyPath) {
  const std::string message = ApplyJsonError(json{{"likelihood_distance", {{"kernel", "gauss"}}}});
  EXPECT_TRUE(Contains(message, "config.likelihood_distance.kernel")) << message;
}

// The kernel is a name, yet a number in its place is reported as "expected a number". Bug
// report: Section::Field should say "expected a string" for std::string fields.
TEST(Config, KernelOfTheWrongTypeAsksForAName) {
  const std::string message = ApplyJsonError(json{{"likelihood_distance", {{"kernel", 3}}}});
  EXPECT_TRUE(Contains(message, "config.likelihood_distance.kernel")) << message;
  EXPECT_TRUE(Contains(message, "expected a string")) << message;
}

// A plain conversion would truncate 20.9 to 20 and wrap 2^32 + 20 to 20: both must be refused.
TEST(Config, FractionalOrOverflowingSlotCountIsRefused) {
  EXPECT_FALSE(ApplyAndValidateError(json{{"likelihood_test", {{"slot_count", 20.9}}}}).empty());
  EXPECT_FALSE(
      ApplyAndValidateError(json{{"likelihood_test", {{"slot_count", 4294967316LL}}}}).empty());
}

TEST(Config, AbsurdValuesAreRefusedByValidateNamingTheOption) {
  struct Case {
    json patch;
    std::string option;
  };
  const Case cases[] = {
      {{{"likelihood_test", {{"slot_count", 0}}}}, "slot_count"},
      {{{"likelihood_test", {{"slot_count", -5}}}}, "slot_count"},
      {{{"likelihood_test", {{"slot_width_m", -0.01}}}}, "slot_width_m"},
      {{{"likelihood_test", {{"match_threshold_m", 0.0}}}}, "match_threshold_m"},
      {{{"likelihood_test", {{"last_slot_distance_m", -1.0}}}}, "last_slot_distance_m"},
      {{{"validation", {{"min_match_ratio", 2.0}}}}, "min_match_ratio"},
      {{{"validation", {{"min_match_ratio", -0.1}}}}, "min_match_ratio"},
      {{{"validation", {{"max_expect_value_m", 0.0}}}}, "max_expect_value_m"},
      {{{"validation", {{"max_cost_ratio", 0.5}}}}, "max_cost_ratio"},
      {{{"likelihood_distance", {{"scale_m", -1.0}}}}, "scale_m"},
      {{{"point_map", {{"cell_size_m", -1.0}}}}, "cell_size_m"},
      {{{"line_sampling_m", 0.0}}, "line_sampling_m"},
      {{{"point_simulation", {{"footprint_factor", -1.0}}}}, "footprint_factor"},
  };
  for (const Case& c : cases) {
    const std::string message = ApplyAndValidateError(c.patch);
    EXPECT_TRUE(Contains(message, c.option)) << c.patch.dump() << " gave '" << message << "'";
  }
}

TEST(Config, ToJsonThenApplyJsonReproducesEveryField) {
  Config changed;
  changed.scoring.test.slot_count = 30;
  changed.scoring.test.slot_width_m = 0.015;
  changed.scoring.test.match_threshold_m = 0.4;
  changed.scoring.test.last_slot_distance_m = 0.6;
  changed.scoring.distance.kernel = RobustKernel::kTukey;
  changed.scoring.distance.scale_m = 0.2;
  changed.scoring.simulation.footprint_factor = 0.5;
  changed.validation.min_match_ratio = 0.2;
  changed.validation.max_expect_value_m = 0.04;
  changed.validation.alpha_m = 0.2;
  changed.validation.max_cost_ratio = 2.0;
  changed.validation.much_less_factor = 4.0;
  changed.point_map.cell_size_m = 0.02;
  changed.point_map.max_point_spacing_m = 0.25;
  changed.line_sampling_m = 0.005;
  changed.mounting.T_robot_laser = {0.1, -0.05, 0.01};
  changed.refiner.method = RefinementMethod::kErrorDescent;
  changed.refiner.ceres.incidence = IncidenceWeighting::kGate;
  changed.refiner.ceres.point_association = PointAssociation::kSimulatedHit;
  changed.refiner.ceres.line_fit_neighbours = 7;
  changed.refiner.error_descent.step_levels = 5;
  changed.refiner.error_descent.diagonal_moves = false;
  changed.refiner.icp.max_correspondence_distance_m = 0.3;
  changed.refiner.icp.max_iterations = 20;
  changed.refiner.icp.point_to_plane = true;
  changed.session.max_refined_candidates = 2;
  changed.session.insert_unvalidated = true;
  changed.session.extension.free_space_margin_per_m = 0.02;
  changed.session.initial_pose = {1.5, -2.0, 0.3};
  changed.log.max_range_m = 81.83;
  changed.log.laser_offset_m = 0.12;
  changed.log.repair_reversed_odometry = false;

  Config read;
  ApplyJson(ToJson(changed), read);
  EXPECT_EQ(ToJson(read), ToJson(changed));
  EXPECT_EQ(read.scoring.test.slot_count, 30);
  EXPECT_EQ(read.scoring.distance.kernel, RobustKernel::kTukey);
  EXPECT_DOUBLE_EQ(read.scoring.simulation.footprint_factor, 0.5);
  EXPECT_DOUBLE_EQ(read.validation.much_less_factor, 4.0);
  EXPECT_DOUBLE_EQ(read.point_map.max_point_spacing_m, 0.25);
  EXPECT_DOUBLE_EQ(read.line_sampling_m, 0.005);
  EXPECT_DOUBLE_EQ(read.mounting.T_robot_laser.yaw_rad, 0.01);
  EXPECT_EQ(read.refiner.method, RefinementMethod::kErrorDescent);
  EXPECT_EQ(read.refiner.ceres.point_association, PointAssociation::kSimulatedHit);
  EXPECT_FALSE(read.refiner.error_descent.diagonal_moves);
  EXPECT_EQ(read.refiner.icp.max_iterations, 20);
  EXPECT_TRUE(read.refiner.icp.point_to_plane);
  EXPECT_DOUBLE_EQ(read.session.initial_pose.yaw_rad, 0.3);
  EXPECT_EQ(read.log.laser_offset_m, std::optional<double>(0.12));
  EXPECT_FALSE(read.log.repair_reversed_odometry);
  // A JSON text round trip, as the file would hold it, too.
  Config from_text;
  ApplyJson(json::parse(ToJson(changed).dump()), from_text);
  EXPECT_EQ(ToJson(from_text), ToJson(changed));
}

TEST(Config, EveryDeclaredOptionIsInToJsonAndNothingElse) {
  const json written = ToJson(Config{});
  std::size_t declared = 0;
  for (const OptionDescription& option : DescribeOptions()) {
    std::string pointer = "/" + option.key;
    std::replace(pointer.begin(), pointer.end(), '.', '/');
    EXPECT_TRUE(written.contains(json::json_pointer(pointer))) << option.key;
    ++declared;
  }
  // Every leaf ToJson writes is a declared option (initial_pose is one option of three numbers).
  std::size_t leaves = 0;
  const json flat = written.flatten();
  for (const auto& [pointer, value] : flat.items())
    leaves += pointer.find("/initial_pose/") == std::string::npos || pointer.back() == '0';
  EXPECT_EQ(leaves, declared);
}

TEST(Config, HelpTextListsEveryKeyWithItsDefault) {
  const std::string help = OptionsHelp();
  for (const OptionDescription& option : DescribeOptions()) {
    EXPECT_TRUE(Contains(help, "  " + option.key + " = " + option.default_value)) << option.key;
    EXPECT_FALSE(option.meaning.empty()) << option.key;
  }
  EXPECT_TRUE(Contains(help, "refinement.icp.max_iterations = 50")) << help;
  EXPECT_TRUE(Contains(help, "log.laser_offset_m = null")) << help;
  EXPECT_TRUE(Contains(help, "validation.max_expect_value_m = 0.1")) << help;
}

TEST(Config, IcpAndLogReaderOptionsAreReachable) {
  Config config;
  ApplyJson(json::parse(R"({"refinement": {"method": "icp",
                                           "icp": {"max_iterations": 7, "point_to_plane": true}},
                            "log": {"laser_offset_m": 0.3, "repair_reversed_odometry": false,
                                    "max_range_m": 81.83}})"),
            config);
  EXPECT_EQ(config.refiner.method, RefinementMethod::kIcp);
  EXPECT_EQ(config.refiner.icp.max_iterations, 7);
  EXPECT_TRUE(config.refiner.icp.point_to_plane);
  ASSERT_TRUE(config.log.laser_offset_m.has_value());
  EXPECT_DOUBLE_EQ(*config.log.laser_offset_m, 0.3);
  EXPECT_FALSE(config.log.repair_reversed_odometry);
  EXPECT_DOUBLE_EQ(config.log.max_range_m, 81.83);
  EXPECT_EQ(ToJson(config).at("log").at("laser_offset_m"), 0.3);
  // null gives the offset back to the log's PARAM.
  ApplyJson(json{{"log", {{"laser_offset_m", nullptr}}}}, config);
  EXPECT_FALSE(config.log.laser_offset_m.has_value());
  EXPECT_TRUE(ToJson(config).at("log").at("laser_offset_m").is_null());
}

TEST(Config, SessionMaxExpectValueIsRefusedNamingItsNewPlace) {
  const std::string message = ApplyJsonError(json{{"session", {{"max_expect_value_m", 0.1}}}});
  EXPECT_TRUE(Contains(message, "config.session.max_expect_value_m")) << message;
  EXPECT_TRUE(Contains(message, "moved to validation.max_expect_value_m")) << message;
}

TEST(Config, ErrorDescentHasNoAlphaOfItsOwn) {
  const std::string message =
      ApplyJsonError(json{{"refinement", {{"error_descent", {{"alpha_m", 0.1}}}}}});
  EXPECT_TRUE(Contains(message, "moved to validation.alpha_m")) << message;
}

TEST(Config, AbsurdMagnitudesAreRefusedNamingTheKeyAndTheRange) {
  struct Case {
    json patch;
    std::string key;
  };
  const Case cases[] = {
      {{{"likelihood_test", {{"slot_width_m", 1e-300}}}}, "config.likelihood_test.slot_width_m"},
      {{{"refinement", {{"ceres", {{"line_fit_neighbours", 1000000000}}}}}},
       "config.refinement.ceres.line_fit_neighbours"},
      {{{"session", {{"initial_pose", {0.0, 0.0, 1e20}}}}}, "config.session.initial_pose"},
      {{{"session", {{"initial_pose", {1e300, 0.0, 0.0}}}}}, "config.session.initial_pose"},
      {{{"mounting", {{"yaw_rad", 100.0}}}}, "config.mounting.yaw_rad"},
      {{{"refinement", {{"icp", {{"max_iterations", 0}}}}}},
       "config.refinement.icp.max_iterations"},
      {{{"log", {{"max_range_m", 1e9}}}}, "config.log.max_range_m"},
      {{{"validation", {{"alpha_m", -1.0}}}}, "config.validation.alpha_m"},
  };
  for (const Case& c : cases) {
    const std::string message = ApplyJsonError(c.patch);
    EXPECT_TRUE(Contains(message, c.key)) << c.patch.dump() << " gave '" << message << "'";
    EXPECT_TRUE(Contains(message, "out of range")) << c.patch.dump() << " gave '" << message << "'";
  }
  // The bounds are sane, not tight: the chapter's and the benchmarks' values pass.
  EXPECT_EQ(ApplyAndValidateError(json{{"likelihood_test", {{"slot_width_m", 1e-4}}}}), "");
  EXPECT_EQ(
      ApplyAndValidateError(json{{"refinement", {{"ceres", {{"line_fit_neighbours", 1000}}}}}}),
      "");
}

TEST(Config, NonFiniteOptionSetInCodeIsRefusedByValidateNamingTheKey) {
  Config config;
  config.scoring.distance.scale_m = std::numeric_limits<double>::infinity();
  try {
    config.Validate();
    ADD_FAILURE() << "an infinite scale was accepted";
  } catch (const std::invalid_argument& error) {
    EXPECT_TRUE(Contains(error.what(), "likelihood_distance.scale_m")) << error.what();
  }
  config = {};
  config.session.initial_pose.yaw_rad = std::nan("");
  EXPECT_THROW(config.Validate(), std::invalid_argument);
}

TEST_F(ConfigFileTest, LoadConfigOverlaysTheFileOnTheDefaults) {
  const Config config = LoadConfig(
      Write(R"({"likelihood_test": {"slot_count": 25}, "validation": {"alpha_m": 0.2}})"));
  EXPECT_EQ(config.scoring.test.slot_count, 25);
  EXPECT_DOUBLE_EQ(config.validation.alpha_m, 0.2);
  EXPECT_DOUBLE_EQ(config.scoring.test.slot_width_m, 0.01);
}

TEST_F(ConfigFileTest, InvalidJsonIsRefusedNamingTheFile) {
  const std::string message = LoadError("{\"likelihood_test\": {\"slot_count\": 20,}");
  EXPECT_TRUE(Contains(message, dir_ + "/config.json")) << message;
  EXPECT_TRUE(Contains(message, "not valid JSON")) << message;
}

TEST_F(ConfigFileTest, EmptyFileIsRefusedNamingTheFile) {
  const std::string message = LoadError("");
  EXPECT_TRUE(Contains(message, dir_ + "/config.json")) << message;
}

TEST_F(ConfigFileTest, UnknownKeyInAFileNamesTheFileAndTheKeyPath) {
  const std::string message = LoadError(R"({"validation": {"nonsense": 1}})");
  EXPECT_TRUE(Contains(message, dir_ + "/config.json")) << message;
  EXPECT_TRUE(Contains(message, "config.validation")) << message;
  EXPECT_TRUE(Contains(message, "'nonsense'")) << message;
}

TEST_F(ConfigFileTest, AbsurdValueInAFileIsRefusedNamingTheFileAndTheOption) {
  const std::string message = LoadError(R"({"likelihood_test": {"slot_count": 0}})");
  EXPECT_TRUE(Contains(message, dir_ + "/config.json")) << message;
  EXPECT_TRUE(Contains(message, "slot_count")) << message;
}

TEST_F(ConfigFileTest, NumberBeyondADoubleIsRefusedNamingTheFile) {
  const std::string message = LoadError(R"({"likelihood_test": {"slot_width_m": 1e400}})");
  EXPECT_TRUE(Contains(message, dir_ + "/config.json")) << message;
  EXPECT_TRUE(Contains(message, "1e400")) << message;
}

TEST_F(ConfigFileTest, DuplicateKeyIsRefusedNamingTheFileAndTheKeyPath) {
  const std::string nested =
      LoadError(R"({"validation": {"alpha_m": 0.1, "min_match_ratio": 0.2, "alpha_m": 0.3}})");
  EXPECT_TRUE(Contains(nested, dir_ + "/config.json")) << nested;
  EXPECT_TRUE(Contains(nested, "config.validation")) << nested;
  EXPECT_TRUE(Contains(nested, "duplicate key 'alpha_m'")) << nested;

  const std::string top = LoadError(R"({"validation": {}, "session": {}, "validation": {}})");
  EXPECT_TRUE(Contains(top, "duplicate key 'validation'")) << top;
  // The same key in two different objects is no duplicate.
  EXPECT_EQ(LoadError(R"({"mounting": {"x_m": 0.1}, "session": {"initial_pose": [0, 0, 0]},
                          "refinement": {"ceres": {"max_outer_iterations": 3},
                                         "icp": {"max_iterations": 3}}})"),
            "");
}

TEST_F(ConfigFileTest, MovedOptionInAFileNamesTheFileAndTheNewKey) {
  const std::string message = LoadError(R"({"session": {"max_expect_value_m": 0.1}})");
  EXPECT_TRUE(Contains(message, dir_ + "/config.json")) << message;
  EXPECT_TRUE(Contains(message, "validation.max_expect_value_m")) << message;
}

TEST_F(ConfigFileTest, AbsurdValueInAFileNamesTheFileAndTheKey) {
  const std::string message = LoadError(R"({"session": {"initial_pose": [0, 0, 1e20]}})");
  EXPECT_TRUE(Contains(message, dir_ + "/config.json")) << message;
  EXPECT_TRUE(Contains(message, "config.session.initial_pose")) << message;
}

TEST_F(ConfigFileTest, MissingFileIsRefusedNamingIt) {
  try {
    LoadConfig(dir_ + "/missing.json");
    ADD_FAILURE() << "no error for a missing file";
  } catch (const std::runtime_error& error) {
    EXPECT_TRUE(Contains(error.what(), dir_ + "/missing.json")) << error.what();
  }
}

}  // namespace
}  // namespace scanloc
