#include "scanloc/io/environment_files.hpp"

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <ostream>
#include <sstream>
#include <stdexcept>

#include "scanloc/common/atomic_file.hpp"
#include "scanloc/io/sequence_sources.hpp"
#include "scanloc/worlds/environment_simulation.hpp"

namespace scanloc {
namespace {

void Comment(std::ostream& out, const std::string& text) {
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);) out << "# " << line << '\n';
}

std::string Centimetres(double value_m) {
  if (!std::isfinite(value_m) || std::abs(value_m * 100.0 - std::round(value_m * 100.0)) > 1e-6)
    throw std::invalid_argument("FormatLineFile: " + std::to_string(value_m) +
                                " m is not a whole number of centimetres");
  char text[32];
  std::snprintf(text, sizeof text, "%.2f", value_m);
  return text;
}

void WriteText(const std::string& path, const std::string& text) {
  WriteFileAtomically(path, [&](std::ostream& out) { out << text; });
}

}  // namespace

std::string FormatLineFile(const LineFile& file) {
  std::ostringstream out;
  Comment(out, file.header);
  for (const SegmentGroup& group : file.groups) {
    Comment(out, group.comment);
    for (const Segment& s : group.segments)
      out << Centimetres(s.a.x()) << ' ' << Centimetres(s.a.y()) << ' ' << Centimetres(s.b.x())
          << ' ' << Centimetres(s.b.y()) << '\n';
  }
  return out.str();
}

EnvironmentFiles WriteEnvironmentFiles(const Environment& environment, unsigned seed,
                                       const std::string& directory, std::size_t max_iterations) {
  std::filesystem::create_directories(directory);
  const std::filesystem::path dir(directory);
  EnvironmentFiles files;
  auto write_lines = [&](const std::string& name, const LineFile& lines) {
    files.paths.push_back((dir / name).string());
    WriteText(files.paths.back(), FormatLineFile(lines));
  };
  write_lines(environment.name + ".lines", environment.map);
  write_lines("world.lines", environment.world);
  for (const MapAddition& addition : environment.map_additions)
    write_lines(addition.file_name, addition.lines);

  const auto iterations = SimulateEnvironment(environment, seed, max_iterations);
  files.paths.push_back((dir / (environment.name + ".seq.jsonl")).string());
  SequenceFileWriter writer(files.paths.back(), environment.mounting);
  for (const SimulatedIteration& simulated : iterations) {
    Iteration iteration;
    iteration.timestamp_s = simulated.timestamp_s;
    iteration.scan = simulated.scan;
    iteration.odometry = simulated.T_odom_robot;
    writer.Write(iteration, simulated.T_world_robot);
  }
  writer.Close();
  files.iterations = iterations.size();
  return files;
}

}  // namespace scanloc
