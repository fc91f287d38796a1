#pragma once
// The chapter's three trial sites (§3.4) rebuilt as simulated environments with ground truth: the
// classroom, the office and the "factory". Each has the architectural line map the localisation is
// given, the world the laser sees (the map's walls, less the openings where it gets no return, plus
// what the map does not hold), a robot path and the laser and odometry models.

#include <Eigen/Core>
#include <string>
#include <vector>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/geometry/pose2d.hpp"
#include "scanloc/maps/line_map.hpp"
#include "scanloc/worlds/laser_simulator.hpp"
#include "scanloc/worlds/robot_path.hpp"

namespace scanloc {

// Segments under one comment, as a line file shows them.
struct SegmentGroup {
  std::string comment;  // written as "# comment" above the segments; empty for none
  std::vector<Segment> segments;
};

// A line file as a person reads it: a header comment, then groups of segments.
struct LineFile {
  std::string header;  // one or more lines, each written with a leading "# "
  std::vector<SegmentGroup> groups;
  LineMap Map() const;  // every segment, in order
};

// A line file written beside the map for the operator to add to it (the office's blinds).
struct MapAddition {
  std::string file_name;
  LineFile lines;
};

struct Environment {
  std::string name;  // "classroom", "office", "factory"
  LineFile map;      // the line map the localisation is given: <name>.lines
  LineFile world;    // every segment the laser sees: world.lines
  std::vector<MapAddition> map_additions;
  LaserMounting mounting;       // the laser on the robot
  LaserSimulatorOptions laser;  // the Acuity: 2,400 beams, 20 m, body sector, dropouts
  Pose2D start;                 // T_world_robot of the first iteration
  std::vector<Eigen::Vector2d> waypoints;
  RobotPathOptions path;
  OdometryNoiseOptions odometry;
  double scan_period_s = 1.0;  // time between iterations
};

// §3.4.1: 6.3 m × 7 m, walls almost parallel, an L-shaped board in the north-east corner; a desk
// and a person not in the map. The map and clutter of datasets/classroom.
Environment MakeClassroom();
// §3.4.2: windows along two walls, the glass giving no return; on the south wall lowered blinds
// 0.25 m from the window plane, and printers and hardware along the north wall, neither in the map.
Environment MakeOffice();
// §3.4.3: 34.4 m × 32.1 m, columns 8.2 m apart, machinery not in the map, walls beyond the reliable
// range, an open gate in the east wall.
Environment MakeFactory();

// "classroom", "office", "factory".
const std::vector<std::string>& EnvironmentNames();
// The environment of that name; throws std::invalid_argument listing the known names.
Environment MakeEnvironment(const std::string& name);

}  // namespace scanloc
