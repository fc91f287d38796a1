// §3.4.2 The office: x runs from the south wall to the north wall (the chapter draws north on the
// right), y from the east wall to the west wall. Windows fill most of the south and east walls;
// the laser passes through the glass and meets nothing within range. Lowered blinds hang 0.25 m
// from the south windows, on the room side: the laser meets them before the window plane, and a
// line drawn for them in the map hides that plane in the simulated scan (Trial c). Printers and
// hardware stand along the north wall. Neither is in the map.

#include "scanloc/worlds/environments.hpp"

namespace scanloc {
namespace {

constexpr double kLength = 7.2;         // south to north, m
constexpr double kWidth = 6.0;          // east to west, m
constexpr double kBlindsOffset = 0.25;  // the blinds' distance from the window plane, m

std::vector<Segment> Box(double x0, double y0, double x1, double y1) {
  return {{{x0, y0}, {x1, y0}}, {{x1, y0}, {x1, y1}}, {{x1, y1}, {x0, y1}}, {{x0, y1}, {x0, y0}}};
}

// The west wall with the door, recessed 0.1 m, next to the north-west corner.
SegmentGroup WestWall() {
  return {"west wall, with the door next to the north-west corner",
          {{{0.0, kWidth}, {5.9, kWidth}},
           {{5.9, kWidth}, {5.9, kWidth + 0.1}},
           {{5.9, kWidth + 0.1}, {6.8, kWidth + 0.1}},
           {{6.8, kWidth + 0.1}, {6.8, kWidth}},
           {{6.8, kWidth}, {kLength, kWidth}}}};
}

SegmentGroup NorthWall() {
  return {"north wall", {{{kLength, 0.0}, {kLength, kWidth}}}};
}

}  // namespace

Environment MakeOffice() {
  Environment e;
  e.name = "office";
  e.map.header =
      "Office after §3.4.2 of the reference chapter (x1 y1 x2 y2, metres): x from the south wall\n"
      "to the north wall, y from the east wall to the west wall. The architectural map: the south\n"
      "and east walls are drawn whole although windows fill most of them; the blinds and the\n"
      "printers are not in it.";
  e.map.groups = {{"south wall (windows)", {{{0.0, 0.0}, {0.0, kWidth}}}},
                  {"east wall (windows)", {{{0.0, 0.0}, {kLength, 0.0}}}},
                  NorthWall(),
                  WestWall()};

  e.world.header =
      "What the laser sees in the office (x1 y1 x2 y2, metres): the walls less the windows, whose\n"
      "glass gives no return, and what the map does not hold: the lowered blinds and the printers\n"
      "and hardware along the north wall.";
  e.world.groups = {{"south wall: the piers either side of the windows",
                     {{{0.0, 0.0}, {0.0, 0.5}}, {{0.0, 5.5}, {0.0, kWidth}}}},
                    {"the lowered blinds, 0.25 m from the south windows",
                     {{{kBlindsOffset, 0.55}, {kBlindsOffset, 5.45}}}},
                    {"east wall: the piers and the window frames",
                     {{{0.0, 0.0}, {0.6, 0.0}},
                      {{2.1, 0.0}, {2.2, 0.0}},
                      {{3.6, 0.0}, {3.7, 0.0}},
                      {{5.1, 0.0}, {5.2, 0.0}},
                      {{6.6, 0.0}, {kLength, 0.0}}}},
                    NorthWall(),
                    {"printers and hardware along the north wall", {}},
                    WestWall()};
  auto& hardware = e.world.groups[4].segments;
  for (const auto& box : {Box(6.55, 0.3, kLength, 1.3), Box(6.6, 1.5, kLength, 2.4),
                          Box(6.5, 2.6, kLength, 3.8), Box(6.6, 4.0, kLength, 5.2)})
    hardware.insert(hardware.end(), box.begin(), box.end());

  e.map_additions = {{"blinds.lines",
                      {"The one line the operator adds to office.lines for the lowered blinds\n"
                       "(Trial c of §3.4.2; x1 y1 x2 y2, metres).",
                       {{"the lowered blinds, 0.25 m from the south windows",
                         {{{kBlindsOffset, 0.55}, {kBlindsOffset, 5.45}}}}}}}};

  e.mounting.T_robot_laser = {0.15, 0.0, 0.0};
  e.laser.dropout_probability = 0.02;
  e.laser.body_from_rad = 2.7;
  e.laser.body_to_rad = M_PI;
  // Trial (b)'s posture, then a loop through the room.
  e.start = {3.6, 3.0, 1.54};
  e.waypoints = {{3.6, 4.8}, {5.6, 4.8}, {5.6, 1.4}, {1.4, 1.4}, {1.4, 4.6}, {3.0, 4.6}};
  e.path.step_m = 0.3;
  e.path.turn_step_rad = 0.35;
  return e;
}

}  // namespace scanloc
