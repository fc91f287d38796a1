// §3.4.3 The "factory", a laboratory of 34.4 m × 32.1 m: the architectural map holds the walls and
// the columns, 8.2 m apart; the world adds the machinery, test rigs and cabinets standing in front
// of the walls, and leaves the gate in the east wall open. Most walls lie beyond the laser's
// reliable range from anywhere on the floor.

#include "scanloc/worlds/environments.hpp"

#include <array>

namespace scanloc {
namespace {

constexpr double kLength = 34.4;                    // x, m
constexpr double kWidth = 32.1;                     // y, m
constexpr double kColumnSpacing = 8.2;              // m
constexpr double kColumnSide = 0.5;                 // m
constexpr double kGateFrom = 14.0, kGateTo = 18.0;  // the gate's span in y on the east wall, m

std::vector<Segment> Box(double x0, double y0, double x1, double y1) {
  return {{{x0, y0}, {x1, y0}}, {{x1, y0}, {x1, y1}}, {{x1, y1}, {x0, y1}}, {{x0, y1}, {x0, y0}}};
}

// Four by four columns, centred in the room.
SegmentGroup Columns() {
  SegmentGroup group{"the columns, 8.2 m apart", {}};
  const double x0 = (kLength - 3 * kColumnSpacing) / 2, y0 = (kWidth - 3 * kColumnSpacing) / 2;
  for (int i = 0; i < 4; ++i)
    for (int j = 0; j < 4; ++j) {
      const double x = x0 + i * kColumnSpacing, y = y0 + j * kColumnSpacing;
      const auto box =
          Box(x - kColumnSide / 2, y - kColumnSide / 2, x + kColumnSide / 2, y + kColumnSide / 2);
      group.segments.insert(group.segments.end(), box.begin(), box.end());
    }
  return group;
}

SegmentGroup Boxes(const char* comment, const std::vector<std::array<double, 4>>& boxes) {
  SegmentGroup group{comment, {}};
  for (const auto& b : boxes) {
    const auto box = Box(b[0], b[1], b[2], b[3]);
    group.segments.insert(group.segments.end(), box.begin(), box.end());
  }
  return group;
}

}  // namespace

Environment MakeFactory() {
  Environment e;
  e.name = "factory";
  e.map.header =
      "The \"factory\" after §3.4.3 of the reference chapter (x1 y1 x2 y2, metres): 34.4 m long,\n"
      "32.1 m wide, from the architectural plans: only the walls and the columns.";
  e.map.groups = {{"walls",
                   {{{0.0, 0.0}, {kLength, 0.0}},
                    {{kLength, 0.0}, {kLength, kWidth}},
                    {{kLength, kWidth}, {0.0, kWidth}},
                    {{0.0, kWidth}, {0.0, 0.0}}}},
                  Columns()};

  e.world.header =
      "What the laser sees in the \"factory\" (x1 y1 x2 y2, metres): the walls, the gate in the\n"
      "east wall open, the columns, and the machinery, test rigs and cabinets the map does not\n"
      "hold.";
  e.world.groups = {
      {"walls, the gate in the east wall open",
       {{{0.0, 0.0}, {kLength, 0.0}},
        {{kLength, 0.0}, {kLength, kGateFrom}},
        {{kLength, kGateTo}, {kLength, kWidth}},
        {{kLength, kWidth}, {0.0, kWidth}},
        {{0.0, kWidth}, {0.0, 0.0}}}},
      Columns(),
      Boxes("concrete blocks",
            {{10.0, 1.0, 12.0, 2.5}, {14.0, 1.0, 16.5, 3.0}, {18.5, 1.5, 20.0, 5.5}}),
      Boxes("the wind tunnel", {{22.5, 5.5, 32.5, 7.0}}),
      Boxes("metal cabinets hiding the walls", {{0.3, 6.0, 0.9, 14.0},
                                                {0.3, 16.0, 0.9, 25.0},
                                                {3.0, 31.2, 12.0, 31.8},
                                                {15.0, 31.2, 26.0, 31.8}}),
      Boxes("test rigs", {{7.0, 10.0, 10.5, 13.5},
                          {13.8, 9.5, 15.8, 14.0},
                          {19.0, 9.5, 20.5, 14.0},
                          {22.3, 18.5, 27.5, 22.5},
                          {27.0, 25.0, 32.0, 28.0}}),
      Boxes("brick and mortar structures",
            {{3.0, 18.0, 8.0, 22.0}, {9.5, 24.0, 12.5, 27.0}, {2.0, 24.0, 4.0, 27.0}}),
      Boxes("crates and small machines", {{11.0, 5.6, 11.8, 6.3},
                                          {24.0, 13.0, 25.0, 14.0},
                                          {28.0, 17.8, 28.8, 18.6},
                                          {32.8, 12.0, 33.6, 13.0}})};

  e.mounting.T_robot_laser = {0.15, 0.0, 0.0};
  e.laser.reliable_range_m = 12.0;  // the Acuity on medium or low reflectance
  e.laser.dropout_probability = 0.02;
  e.laser.body_from_rad = 2.7;
  e.laser.body_to_rad = M_PI;
  // From the lower-left corner along the corridors between the columns to the gate, then turned
  // to face the interior (the chapter's iteration 23).
  e.start = {2.5, 1.8, 0.73};
  e.waypoints = {{3.0, 7.85},   {17.2, 7.85},  {17.2, 16.05},
                 {25.4, 16.05}, {32.0, 16.05}, {31.0, 17.0}};
  e.path.step_m = 0.8;  // the chapter's robot moved step by step between acquisitions
  e.path.turn_step_rad = 0.4;
  return e;
}

}  // namespace scanloc
