#pragma once
// The simulated environments' stored sequences, loaded whole for the tests (they are small).

#include <string>
#include <vector>

#include "scanloc/io/sequence_sources.hpp"
#include "scanloc/maps/line_map.hpp"

namespace scanloc::testing {

inline std::string EnvironmentDir(const std::string& name) {
  return std::string(SCANLOC_SOURCE_DIR) + "/datasets/" + name;
}

struct StoredSequence {
  LaserMounting mounting;
  std::vector<Iteration> iterations;
  std::vector<Pose2D> truth;  // T_world_robot, one per iteration
};

// datasets/<name>/<name>.seq.jsonl; every iteration must have its truth.
inline StoredSequence LoadStoredSequence(const std::string& name) {
  SequenceFileSource source(EnvironmentDir(name) + "/" + name + ".seq.jsonl");
  StoredSequence sequence;
  sequence.mounting = source.mounting();
  Iteration iteration;
  while (source.Next(iteration)) {
    if (!source.truth()) throw std::runtime_error(iteration.origin + ": no truth");
    sequence.iterations.push_back(iteration);
    sequence.truth.push_back(*source.truth());
  }
  return sequence;
}

inline LineMap ReadEnvironmentLines(const std::string& name, const std::string& file) {
  return ReadLineMap(EnvironmentDir(name) + "/" + file);
}

}  // namespace scanloc::testing
