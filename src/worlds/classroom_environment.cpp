// §3.4.1 The classroom: the map and clutter of datasets/classroom (classroom.lines, clutter.lines)
// and a loop around the room's free floor.

#include "scanloc/worlds/environments.hpp"

namespace scanloc {
namespace {

// The walls, almost parallel (the room is 6.3 m × 7 m, skewed by 2 cm).
SegmentGroup Walls() {
  return {"",
          {{{0.00, 0.00}, {6.30, 0.02}},
           {{6.30, 0.02}, {6.32, 7.00}},
           {{6.32, 7.00}, {0.00, 7.00}},
           {{0.00, 7.00}, {0.00, 0.00}}}};
}

// Added before the trials so that the room and its mirror image differ.
SegmentGroup LShapedBoard() {
  return {"the L-shaped board, north-east corner",
          {{{5.40, 6.00}, {6.00, 6.00}}, {{6.00, 6.00}, {6.00, 6.60}}}};
}

std::vector<Segment> Box(double x0, double y0, double x1, double y1) {
  return {{{x0, y0}, {x1, y0}}, {{x1, y0}, {x1, y1}}, {{x1, y1}, {x0, y1}}, {{x0, y1}, {x0, y0}}};
}

}  // namespace

Environment MakeClassroom() {
  Environment e;
  e.name = "classroom";
  e.map.header =
      "Classroom after §3.4.1 of the reference chapter: a rectangular room, walls almost "
      "parallel,\nwith an L-shaped board in the north-east corner added to break the room's "
      "symmetry.\nx1 y1 x2 y2 (metres). North wall on top (y = 7.0).";
  e.map.groups = {Walls(), LShapedBoard()};
  e.world.header =
      "What the laser sees in the classroom (x1 y1 x2 y2, metres): the map (classroom.lines) and\n"
      "what it does not hold (clutter.lines), the teacher's desk and a person near the door.";
  e.world.groups = {Walls(),
                    LShapedBoard(),
                    {"the teacher's desk", Box(2.40, 0.60, 3.60, 1.20)},
                    {"a person standing near the door", Box(4.00, 5.20, 4.30, 5.45)}};
  e.mounting.T_robot_laser = {0.15, 0.0, 0.0};
  e.laser.dropout_probability = 0.02;
  e.laser.body_from_rad = 2.7;  // the robot's body behind the laser, as in datasets/classroom
  e.laser.body_to_rad = M_PI;
  // The chapter's true posture of Table 2, then a loop clear of the desk and the person.
  e.start = {1.126, 3.112, 0.0463};
  e.waypoints = {{4.6, 3.2}, {4.9, 4.8}, {4.6, 2.0}, {1.3, 2.0},
                 {0.9, 1.0}, {1.3, 4.6}, {3.4, 4.6}};
  e.path.step_m = 0.3;
  e.path.turn_step_rad = 0.45;
  return e;
}

}  // namespace scanloc
