#include "scanloc/config/config.hpp"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <nlohmann/json.hpp>
#include <set>
#include <sstream>
#include <stdexcept>
#include <type_traits>

#include "option_table.hpp"

namespace scanloc {
namespace {

using config_table::Bounds;
using nlohmann::json;

// Names of the enumerations a config spells out.
void FromName(const std::string& name, RobustKernel& kernel) {
  kernel = ParseRobustKernel(name);
}
void FromName(const std::string& name, RefinementMethod& method) {
  method = ParseRefinementMethod(name);
}
void FromName(const std::string& name, IncidenceWeighting& weighting) {
  weighting = ParseIncidenceWeighting(name);
}
void FromName(const std::string& name, PointAssociation& association) {
  association = ParsePointAssociation(name);
}

std::string Number(double value) {
  std::ostringstream text;
  text << std::setprecision(10) << value;
  return text.str();
}

std::string RangeText(Bounds bounds) {
  return "[" + Number(bounds.min) + ", " + Number(bounds.max) + "]";
}

// "" when `value` is finite and within `bounds`, else what is wrong with it.
std::string RangeProblem(double value, Bounds bounds, bool whole) {
  if (std::isfinite(value) && value >= bounds.min && value <= bounds.max) return "";
  return Number(value) + " is out of range: expected a " + (whole ? "whole " : "finite ") +
         "number in " + RangeText(bounds);
}

std::string PoseProblem(const Pose2D& pose, Bounds position, Bounds heading) {
  std::string problem = RangeProblem(pose.x_m, position, false);
  if (problem.empty()) problem = RangeProblem(pose.y_m, position, false);
  if (problem.empty()) problem = RangeProblem(pose.yaw_rad, heading, false);
  return problem.empty() ? "" : "[x, y, yaw]: " + problem;
}

// The JSON pointer of a dotted key: "a.b" → "/a/b".
json::json_pointer Pointer(const std::string& key) {
  std::string pointer = "/" + key;
  for (char& ch : pointer)
    if (ch == '.') ch = '/';
  return json::json_pointer(pointer);
}

// Collects the declared keys and the sections that hold them.
struct KeyCollector {
  std::set<std::string> keys, sections;
  void Add(const std::string& key) {
    keys.insert(key);
    for (auto dot = key.find('.'); dot != std::string::npos; dot = key.find('.', dot + 1))
      sections.insert(key.substr(0, dot));
  }
  template <class T>
  void operator()(const char* key, T&, Bounds, const char*) {
    Add(key);
  }
  template <class T>
  void operator()(const char* key, T&, const char*) {
    Add(key);
  }
  void operator()(const char* key, const Pose2D&, Bounds, Bounds, const char*) { Add(key); }
};

const KeyCollector& DeclaredKeys() {
  static const KeyCollector collector = [] {
    KeyCollector keys;
    const Config defaults;
    config_table::VisitOptions(defaults, keys);
    return keys;
  }();
  return collector;
}

// Refuses members of `object` (at `prefix`, "" for the top) that no option declares, naming
// their path; a key that moved names its new place.
void RefuseUnknownKeys(const json& object, const std::string& prefix) {
  const std::string where = prefix.empty() ? "config" : "config." + prefix;
  if (!object.is_object()) throw std::runtime_error(where + ": expected a JSON object");
  const KeyCollector& declared = DeclaredKeys();
  for (const auto& [key, value] : object.items()) {
    const std::string path = prefix.empty() ? key : prefix + "." + key;
    for (const auto& moved : config_table::kMovedOptions)
      if (path == moved.old_key)
        throw std::runtime_error("config." + path + ": this option moved to " + moved.new_key +
                                 "; set that instead");
    if (key.find('.') != std::string::npos)  // "a.b" would pass as a path, then be ignored
      throw std::runtime_error(where + ": unknown key '" + key +
                               "' (sections nest as objects: {\"a\": {\"b\": ...}})");
    if (declared.keys.count(path)) continue;
    if (!declared.sections.count(path))
      throw std::runtime_error(where + ": unknown key '" + key + "'");
    RefuseUnknownKeys(value, path);
  }
}

// Reads every declared key present in a JSON object (already checked by RefuseUnknownKeys),
// refusing values of the wrong type or out of their bounds with the key's path.
class JsonReader {
 public:
  explicit JsonReader(const json& root) : root_(root) {}

  template <class T>
  void operator()(const char* key, T& field, Bounds bounds, const char*) {
    const json* node = Find(key);
    if (!node) return;
    const std::string where = std::string("config.") + key;
    if constexpr (std::is_same_v<T, int>) {
      if (!node->is_number_integer()) throw std::runtime_error(where + ": expected a whole number");
      field = static_cast<int>(Checked(node->get<double>(), where, bounds, true));
    } else if constexpr (std::is_same_v<T, std::optional<double>>) {
      if (node->is_null())
        field.reset();
      else
        field = Checked(NumberAt(*node, where), where, bounds, false);
    } else {
      field = Checked(NumberAt(*node, where), where, bounds, false);
    }
  }

  template <class T>
  void operator()(const char* key, T& field, const char*) {
    const json* node = Find(key);
    if (!node) return;
    const std::string where = std::string("config.") + key;
    if constexpr (std::is_same_v<T, bool>) {
      if (!node->is_boolean()) throw std::runtime_error(where + ": expected true or false");
      field = node->get<bool>();
    } else {
      if (!node->is_string()) throw std::runtime_error(where + ": expected a string (a name)");
      try {
        FromName(node->get<std::string>(), field);
      } catch (const std::invalid_argument& e) {
        throw std::runtime_error(where + ": " + e.what());
      }
    }
  }

  void operator()(const char* key, Pose2D& pose, Bounds position, Bounds heading, const char*) {
    const json* node = Find(key);
    if (!node) return;
    const std::string where = std::string("config.") + key;
    if (!node->is_array() || node->size() != 3 ||
        !std::all_of(node->begin(), node->end(), [](const json& v) { return v.is_number(); }))
      throw std::runtime_error(where + ": expected [x, y, yaw], three numbers");
    const Pose2D read{(*node)[0].get<double>(), (*node)[1].get<double>(), (*node)[2].get<double>()};
    if (const std::string problem = PoseProblem(read, position, heading); !problem.empty())
      throw std::runtime_error(where + " " + problem);
    pose = read;
  }

 private:
  const json* Find(const char* key) const {
    const auto pointer = Pointer(key);
    return root_.contains(pointer) ? &root_.at(pointer) : nullptr;
  }
  static double NumberAt(const json& node, const std::string& where) {
    if (!node.is_number()) throw std::runtime_error(where + ": expected a number");
    return node.get<double>();
  }
  static double Checked(double value, const std::string& where, Bounds bounds, bool whole) {
    if (const std::string problem = RangeProblem(value, bounds, whole); !problem.empty())
      throw std::runtime_error(where + ": " + problem);
    return value;
  }

  const json& root_;
};

// Writes every option at its key path.
struct JsonWriter {
  json root = json::object();
  template <class T>
  void operator()(const char* key, const T& field, Bounds, const char*) {
    if constexpr (std::is_same_v<T, std::optional<double>>)
      root[Pointer(key)] = field ? json(*field) : json(nullptr);
    else
      root[Pointer(key)] = field;
  }
  template <class T>
  void operator()(const char* key, const T& field, const char*) {
    if constexpr (std::is_enum_v<T>)
      root[Pointer(key)] = ToString(field);
    else
      root[Pointer(key)] = field;
  }
  void operator()(const char* key, const Pose2D& pose, Bounds, Bounds, const char*) {
    root[Pointer(key)] = {pose.x_m, pose.y_m, pose.yaw_rad};
  }
};

// Checks the bounds of every option of a Config built in code (ApplyJson checks what it reads).
struct BoundsChecker {
  template <class T>
  void operator()(const char* key, const T& field, Bounds bounds, const char*) const {
    std::string problem;
    if constexpr (std::is_same_v<T, std::optional<double>>) {
      if (field) problem = RangeProblem(*field, bounds, false);
    } else {
      problem = RangeProblem(field, bounds, std::is_same_v<T, int>);
    }
    if (!problem.empty()) throw std::invalid_argument(std::string(key) + ": " + problem);
  }
  template <class T>
  void operator()(const char*, const T&, const char*) const {}
  void operator()(const char* key, const Pose2D& pose, Bounds position, Bounds heading,
                  const char*) const {
    if (const std::string problem = PoseProblem(pose, position, heading); !problem.empty())
      throw std::invalid_argument(std::string(key) + " " + problem);
  }
};

// The help text's line for each option.
struct Describer {
  const json defaults = ToJson(Config{});
  std::vector<OptionDescription> options;
  void Add(const char* key, std::string range, const char* meaning) {
    options.push_back({key, defaults.at(Pointer(key)).dump(), std::move(range), meaning});
  }
  template <class T>
  void operator()(const char* key, const T&, Bounds bounds, const char* meaning) {
    Add(key, RangeText(bounds), meaning);
  }
  template <class T>
  void operator()(const char* key, const T&, const char* meaning) {
    Add(key, std::is_same_v<T, bool> ? "true or false" : "a name", meaning);
  }
  void operator()(const char* key, const Pose2D&, Bounds position, Bounds heading,
                  const char* meaning) {
    Add(key, "x, y in " + RangeText(position) + ", yaw in " + RangeText(heading), meaning);
  }
};

// Parses JSON text, refusing an object that holds a key twice (the parser would keep the last
// silently), with the path of the object.
json ParseRefusingDuplicateKeys(std::istream& in) {
  struct Level {
    std::string path;
    bool object = false;
    std::set<std::string> keys;
    std::string last_key;
  };
  std::vector<Level> levels;
  const json::parser_callback_t callback = [&levels](int, json::parse_event_t event, json& parsed) {
    using Event = json::parse_event_t;
    if (event == Event::object_start || event == Event::array_start) {
      std::string path = "config";
      if (!levels.empty())
        path = levels.back().path + (levels.back().object ? "." + levels.back().last_key : "[]");
      levels.push_back({path, event == Event::object_start, {}, {}});
    } else if (event == Event::object_end || event == Event::array_end) {
      levels.pop_back();
    } else if (event == Event::key) {
      Level& level = levels.back();
      level.last_key = parsed.get<std::string>();
      if (!level.keys.insert(level.last_key).second)
        throw std::runtime_error(level.path + ": duplicate key '" + level.last_key +
                                 "' (write each key once)");
    }
    return true;
  };
  return json::parse(in, callback);
}

}  // namespace

void Config::Validate() const {
  BoundsChecker bounds;
  config_table::VisitOptions(*this, bounds);
  scoring.test.Validate();
  scoring.distance.Validate();
  validation.Validate();
  PointMap check(point_map);  // validates its options
  refiner.ceres.Validate();
  refiner.error_descent.Validate();
  refiner.icp.Validate();
  session.Validate();
  localise.Validate();
  log.Validate();
  occupancy_grid.Validate();
}

void ApplyJson(const json& root, Config& config) {
  RefuseUnknownKeys(root, "");
  JsonReader reader(root);
  config_table::VisitOptions(config, reader);
}

Config LoadConfig(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open config file " + path);
  json root;
  try {
    root = ParseRefusingDuplicateKeys(in);
  } catch (const json::exception& e) {
    throw std::runtime_error(path + ": not valid JSON: " + e.what());
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(path + ": " + e.what());
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

json ToJson(const Config& config) {
  JsonWriter writer;
  config_table::VisitOptions(config, writer);
  return writer.root;
}

std::vector<OptionDescription> DescribeOptions() {
  Describer describer;
  const Config defaults;
  config_table::VisitOptions(defaults, describer);
  return describer.options;
}

std::string OptionsHelp() {
  std::ostringstream text;
  text << "Options of the JSON config (--config FILE) and of --set KEY=VALUE: key = default,\n"
          "accepted values, meaning. A file holds any subset as nested objects, e.g.\n"
          "{\"likelihood_test\": {\"slot_count\": 30}}.\n";
  for (const OptionDescription& option : DescribeOptions())
    text << "\n  " << option.key << " = " << option.default_value << "   " << option.accepted
         << "\n      " << option.meaning << '\n';
  return text.str();
}

}  // namespace scanloc
