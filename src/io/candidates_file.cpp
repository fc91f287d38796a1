#include "scanloc/io/candidates_file.hpp"

#include <cmath>
#include <fstream>
#include <iomanip>
#include <stdexcept>

#include "scanloc/common/atomic_file.hpp"
#include "scanloc/common/bounded_line.hpp"
#include "scanloc/common/parse_error.hpp"

namespace scanloc {

std::vector<Candidate> ReadCandidatesFile(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error("cannot open candidates file " + path);
  std::vector<Candidate> candidates;
  std::string line;
  for (std::size_t number = 1; ReadBoundedLine(in, line, path, number); ++number) {
    const auto fields = SplitFields(line, 4);
    if (fields.empty()) continue;
    if (fields.size() != 3 && fields.size() != 4)
      throw ParseError(path, number,
                       "expected 'x y theta [label]' (metres, radians), got " +
                           std::to_string(fields.size()) + " fields");
    Candidate c;
    c.T_world_robot = {ParseFiniteDouble(fields[0], path, number, "x in metres"),
                       ParseFiniteDouble(fields[1], path, number, "y in metres"),
                       ParseFiniteDouble(fields[2], path, number, "theta in radians")};
    c.label = fields.size() == 4 ? fields[3] : "p" + std::to_string(candidates.size());
    candidates.push_back(c);
  }
  return candidates;
}

void WriteCandidatesFile(const std::vector<Candidate>& candidates, const std::string& path) {
  // Refuse what ReadCandidatesFile could not read back as written.
  for (const auto& c : candidates) {
    const Pose2D& p = c.T_world_robot;
    if (!std::isfinite(p.x_m) || !std::isfinite(p.y_m) || !std::isfinite(p.yaw_rad))
      throw std::invalid_argument("WriteCandidatesFile: candidate '" + c.label +
                                  "' has a non-finite posture");
    if (c.label.empty() || c.label.find_first_of(" \t\r\n#") != std::string::npos)
      throw std::invalid_argument("WriteCandidatesFile: label '" + c.label +
                                  "' must be one word without '#'");
  }
  WriteFileAtomically(path, [&](std::ostream& out) {
    out << "# x y theta label (robot posture: metres, radians)\n" << std::setprecision(10);
    for (const auto& c : candidates)
      out << c.T_world_robot.x_m << ' ' << c.T_world_robot.y_m << ' ' << c.T_world_robot.yaw_rad
          << ' ' << c.label << '\n';
  });
}

}  // namespace scanloc
