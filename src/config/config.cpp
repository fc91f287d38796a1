#include "scanloc/config/config.hpp"

#include <algorithm>
#include <fstream>
#include <limits>
#include <nlohmann/json.hpp>
#include <stdexcept>
#include <type_traits>

namespace scanloc {
namespace {

using nlohmann::json;

// Reads the members of one JSON object into fields, refusing unknown keys.
class Section {
 public:
  Section(const json& object, std::string path) : object_(object), path_(std::move(path)) {
    if (!object_.is_object()) throw std::runtime_error(path_ + ": expected a JSON object");
  }
  template <class T>
  Section& Field(const char* key, T& field) {
    known_.push_back(key);
    if (const auto it = object_.find(key); it != object_.end()) {
      const std::string where = path_ + "." + key;
      if constexpr (std::is_same_v<T, int>) {
        // get<int>() would truncate 20.9 and wrap 2^32 + 20: refuse both.
        if (!it->is_number_integer() || *it < std::numeric_limits<int>::min() ||
            *it > std::numeric_limits<int>::max())
          throw std::runtime_error(where + ": expected a whole number");
        field = it->template get<int>();
      } else if constexpr (std::is_same_v<T, bool>) {
        if (!it->is_boolean()) throw std::runtime_error(where + ": expected true or false");
        field = it->template get<bool>();
      } else if constexpr (std::is_same_v<T, std::vector<double>>) {
        if (!it->is_array() ||
            !std::all_of(it->begin(), it->end(), [](const json& v) { return v.is_number(); }))
          throw std::runtime_error(where + ": expected an array of numbers");
        field = it->template get<std::vector<double>>();
      } else if constexpr (std::is_same_v<T, std::string>) {
        if (!it->is_string()) throw std::runtime_error(where + ": expected a string (a name)");
        field = it->template get<std::string>();
      } else {
        if (!it->is_number()) throw std::runtime_error(where + ": expected a number");
        field = it->template get<T>();
      }
    }
    return *this;
  }
  Section Child(const char* key) {
    known_.push_back(key);
    const auto it = object_.find(key);
    return Section(it != object_.end() ? *it : empty_, path_ + "." + key);
  }
  bool Has(const char* key) const { return object_.contains(key); }
  void RefuseUnknown() const {
    for (const auto& [key, value] : object_.items())
      if (std::find(known_.begin(), known_.end(), key) == known_.end())
        throw std::runtime_error(path_ + ": unknown key '" + key + "'");
  }

 private:
  static inline const json empty_ = json::object();
  const json& object_;
  std::string path_;
  std::vector<std::string> known_;
};

}  // namespace

void Config::Validate() const {
  scoring.test.Validate();
  scoring.distance.Validate();
  validation.Validate();
  PointMap check(point_map);  // validates its options
  if (!(line_sampling_m > 0.0)) throw std::invalid_argument("line_sampling_m must be positive");
  refiner.ceres.Validate();
  refiner.error_descent.Validate();
  session.Validate();
  if (!(scoring.simulation.footprint_factor >= 0.0))
    throw std::invalid_argument("point_simulation.footprint_factor must be >= 0");
}

void ApplyJson(const json& root, Config& c) {
  Section top(root, "config");
  auto test = top.Child("likelihood_test");
  test.Field("slot_count", c.scoring.test.slot_count)
      .Field("slot_width_m", c.scoring.test.slot_width_m)
      .Field("match_threshold_m", c.scoring.test.match_threshold_m)
      .Field("last_slot_distance_m", c.scoring.test.last_slot_distance_m)
      .RefuseUnknown();
  auto distance = top.Child("likelihood_distance");
  std::string kernel = ToString(c.scoring.distance.kernel);
  distance.Field("kernel", kernel).Field("scale_m", c.scoring.distance.scale_m).RefuseUnknown();
  try {
    c.scoring.distance.kernel = ParseRobustKernel(kernel);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("config.likelihood_distance.kernel: ") + e.what());
  }
  top.Child("point_simulation")
      .Field("footprint_factor", c.scoring.simulation.footprint_factor)
      .RefuseUnknown();
  top.Child("validation")
      .Field("min_match_ratio", c.validation.min_match_ratio)
      .Field("max_expect_value_m", c.validation.max_expect_value_m)
      .Field("alpha_m", c.validation.alpha_m)
      .Field("max_cost_ratio", c.validation.max_cost_ratio)
      .Field("much_less_factor", c.validation.much_less_factor)
      .RefuseUnknown();
  top.Child("point_map")
      .Field("cell_size_m", c.point_map.cell_size_m)
      .Field("max_point_spacing_m", c.point_map.max_point_spacing_m)
      .RefuseUnknown();
  top.Field("line_sampling_m", c.line_sampling_m);
  top.Child("mounting")
      .Field("x_m", c.mounting.T_robot_laser.x_m)
      .Field("y_m", c.mounting.T_robot_laser.y_m)
      .Field("yaw_rad", c.mounting.T_robot_laser.yaw_rad)
      .RefuseUnknown();
  auto refinement = top.Child("refinement");
  std::string method = ToString(c.refiner.method);
  refinement.Field("method", method);
  auto ceres = refinement.Child("ceres");
  std::string incidence = ToString(c.refiner.ceres.incidence);
  std::string association = ToString(c.refiner.ceres.point_association);
  ceres.Field("max_outer_iterations", c.refiner.ceres.max_outer_iterations)
      .Field("max_solver_iterations", c.refiner.ceres.max_solver_iterations)
      .Field("translation_tolerance_m", c.refiner.ceres.translation_tolerance_m)
      .Field("rotation_tolerance_rad", c.refiner.ceres.rotation_tolerance_rad)
      .Field("incidence", incidence)
      .Field("point_association", association)
      .Field("max_incidence_rad", c.refiner.ceres.max_incidence_rad)
      .Field("max_residual_m", c.refiner.ceres.max_residual_m)
      .Field("line_fit_neighbours", c.refiner.ceres.line_fit_neighbours)
      .Field("line_fit_radius_m", c.refiner.ceres.line_fit_radius_m)
      .Field("max_line_thickness", c.refiner.ceres.max_line_thickness)
      .Field("degeneracy_ratio", c.refiner.ceres.degeneracy_ratio)
      .RefuseUnknown();
  refinement.Child("error_descent")
      .Field("initial_step_m", c.refiner.error_descent.initial_step_m)
      .Field("initial_step_rad", c.refiner.error_descent.initial_step_rad)
      .Field("step_levels", c.refiner.error_descent.step_levels)
      .Field("max_moves_per_level", c.refiner.error_descent.max_moves_per_level)
      .RefuseUnknown();
  refinement.RefuseUnknown();
  try {
    c.refiner.method = ParseRefinementMethod(method);
    c.refiner.ceres.incidence = ParseIncidenceWeighting(incidence);
    c.refiner.ceres.point_association = ParsePointAssociation(association);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(std::string("config.refinement: ") + e.what());
  }
  std::vector<double> initial{c.session.initial_pose.x_m, c.session.initial_pose.y_m,
                              c.session.initial_pose.yaw_rad};
  auto session = top.Child("session");
  session.Field("heading_spread_rad", c.session.heading_spread_rad)
      .Field("heading_step_rad", c.session.heading_step_rad)
      .Field("max_refined_candidates", c.session.max_refined_candidates)
      .Field("max_expect_value_m", c.session.max_expect_value_m)
      .Field("heading_candidates_min_turn_rad", c.session.heading_candidates_min_turn_rad)
      .Field("localise_translation_m", c.session.localise_translation_m)
      .Field("localise_rotation_rad", c.session.localise_rotation_rad)
      .Field("insert_translation_m", c.session.insert_translation_m)
      .Field("insert_rotation_rad", c.session.insert_rotation_rad)
      .Field("insert_unvalidated", c.session.insert_unvalidated)
      .Field("free_space_margin_m", c.session.extension.free_space_margin_m)
      .Field("free_space_margin_per_m", c.session.extension.free_space_margin_per_m)
      .Field("initial_pose", initial)
      .RefuseUnknown();
  if (initial.size() != 3)
    throw std::runtime_error("config.session.initial_pose: expected [x, y, yaw]");
  c.session.initial_pose = {initial[0], initial[1], initial[2]};
  top.RefuseUnknown();
}

Config LoadConfig(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open config file " + path);
  json root;
  try {
    root = json::parse(in);
  } catch (const json::parse_error& e) {
    throw std::runtime_error(path + ": not valid JSON: " + e.what());
  }
  Config config;
  try {
    ApplyJson(root, config);
    config.Validate();
  } catch (const std::exception& e) {
    throw std::runtime_error(path + ": " + e.what());
  }
  return config;
}

json ToJson(const Config& c) {
  return {
      {"likelihood_test",
       {{"slot_count", c.scoring.test.slot_count},
        {"slot_width_m", c.scoring.test.slot_width_m},
        {"match_threshold_m", c.scoring.test.match_threshold_m},
        {"last_slot_distance_m", c.scoring.test.last_slot_distance_m}}},
      {"likelihood_distance",
       {{"kernel", ToString(c.scoring.distance.kernel)}, {"scale_m", c.scoring.distance.scale_m}}},
      {"point_simulation", {{"footprint_factor", c.scoring.simulation.footprint_factor}}},
      {"validation",
       {{"min_match_ratio", c.validation.min_match_ratio},
        {"max_expect_value_m", c.validation.max_expect_value_m},
        {"alpha_m", c.validation.alpha_m},
        {"max_cost_ratio", c.validation.max_cost_ratio},
        {"much_less_factor", c.validation.much_less_factor}}},
      {"point_map",
       {{"cell_size_m", c.point_map.cell_size_m},
        {"max_point_spacing_m", c.point_map.max_point_spacing_m}}},
      {"line_sampling_m", c.line_sampling_m},
      {"mounting",
       {{"x_m", c.mounting.T_robot_laser.x_m},
        {"y_m", c.mounting.T_robot_laser.y_m},
        {"yaw_rad", c.mounting.T_robot_laser.yaw_rad}}},
      {"refinement",
       {{"method", ToString(c.refiner.method)},
        {"ceres",
         {{"max_outer_iterations", c.refiner.ceres.max_outer_iterations},
          {"max_solver_iterations", c.refiner.ceres.max_solver_iterations},
          {"translation_tolerance_m", c.refiner.ceres.translation_tolerance_m},
          {"rotation_tolerance_rad", c.refiner.ceres.rotation_tolerance_rad},
          {"incidence", ToString(c.refiner.ceres.incidence)},
          {"point_association", ToString(c.refiner.ceres.point_association)},
          {"max_incidence_rad", c.refiner.ceres.max_incidence_rad},
          {"max_residual_m", c.refiner.ceres.max_residual_m},
          {"line_fit_neighbours", c.refiner.ceres.line_fit_neighbours},
          {"line_fit_radius_m", c.refiner.ceres.line_fit_radius_m},
          {"max_line_thickness", c.refiner.ceres.max_line_thickness},
          {"degeneracy_ratio", c.refiner.ceres.degeneracy_ratio}}},
        {"error_descent",
         {{"initial_step_m", c.refiner.error_descent.initial_step_m},
          {"initial_step_rad", c.refiner.error_descent.initial_step_rad},
          {"step_levels", c.refiner.error_descent.step_levels},
          {"max_moves_per_level", c.refiner.error_descent.max_moves_per_level}}}}},
      {"session",
       {{"heading_spread_rad", c.session.heading_spread_rad},
        {"heading_step_rad", c.session.heading_step_rad},
        {"max_refined_candidates", c.session.max_refined_candidates},
        {"max_expect_value_m", c.session.max_expect_value_m},
        {"heading_candidates_min_turn_rad", c.session.heading_candidates_min_turn_rad},
        {"localise_translation_m", c.session.localise_translation_m},
        {"localise_rotation_rad", c.session.localise_rotation_rad},
        {"insert_translation_m", c.session.insert_translation_m},
        {"insert_rotation_rad", c.session.insert_rotation_rad},
        {"insert_unvalidated", c.session.insert_unvalidated},
        {"free_space_margin_m", c.session.extension.free_space_margin_m},
        {"free_space_margin_per_m", c.session.extension.free_space_margin_per_m},
        {"initial_pose",
         {c.session.initial_pose.x_m, c.session.initial_pose.y_m,
          c.session.initial_pose.yaw_rad}}}},
  };
}

}  // namespace scanloc
