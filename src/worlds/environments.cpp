#include "scanloc/worlds/environments.hpp"

#include <stdexcept>

namespace scanloc {

LineMap LineFile::Map() const {
  LineMap map;
  for (const SegmentGroup& group : groups)
    map.segments.insert(map.segments.end(), group.segments.begin(), group.segments.end());
  return map;
}

const std::vector<std::string>& EnvironmentNames() {
  static const std::vector<std::string> names{"classroom", "office", "factory"};
  return names;
}

Environment MakeEnvironment(const std::string& name) {
  if (name == "classroom") return MakeClassroom();
  if (name == "office") return MakeOffice();
  if (name == "factory") return MakeFactory();
  std::string known;
  for (const std::string& n : EnvironmentNames()) known += (known.empty() ? "" : ", ") + n;
  throw std::invalid_argument("unknown environment '" + name + "': expected one of " + known);
}

}  // namespace scanloc
