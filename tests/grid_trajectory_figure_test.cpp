// TrajectoryOverGridFigure: the grid a pixel per cell, the path at full precision, labels that
// never overlap where the path returns.
#include "scanloc/report/grid_trajectory_figure.hpp"

#include <gtest/gtest.h>

#include <regex>

#include "scanloc/report/label_placer.hpp"
#include "scanloc/report/png_image.hpp"

namespace scanloc {
namespace {

// A 200 × 100 cell grid of 5 cm from (-1, -2) m: free inside, a wall along the bottom row.
OccupancyGridImage Grid() {
  OccupancyGridImage grid;
  grid.resolution_m = 0.05;
  grid.origin_m = {-1.0, -2.0};
  grid.width = 200;
  grid.height = 100;
  grid.pixels.assign(grid.width * grid.height, kPgmFree);
  for (std::size_t x = 0; x < grid.width; ++x)
    grid.pixels[(grid.height - 1) * grid.width + x] = kPgmOccupied;
  return grid;
}

// Out along x and back over the same postures, every iteration linked.
std::vector<IterationRow> OutAndBack() {
  std::vector<IterationRow> rows;
  for (int i = 0; i < 20; ++i) {
    IterationRow row;
    row.index = rows.size();
    row.validated = true;
    const int step = i < 10 ? i : 19 - i;
    row.T_world_robot = Pose2D(0.123456 + 0.3 * step, 0.5, 0.0);
    rows.push_back(row);
  }
  return rows;
}

struct Label {
  double x0, y0, x1, y1;
};

std::vector<Label> Labels(const std::string& svg) {
  std::vector<Label> labels;
  const std::regex text(
      R"re(<text x="([-0-9.]+)" y="([-0-9.]+)" font-size="10"[^>]*>([0-9a-z]+)</text>)re");
  for (auto it = std::sregex_iterator(svg.begin(), svg.end(), text); it != std::sregex_iterator();
       ++it) {
    const double x = std::stod((*it)[1]), y = std::stod((*it)[2]);
    labels.push_back({x, y - 8.0, x + EstimateTextWidth((*it)[3], 10.0), y + 2.0});
  }
  return labels;
}

TEST(GridTrajectoryFigure, FitsTheGridAtOneScaleAndEmbedsItAPixelPerCell) {
  const std::vector<IterationRow> rows = OutAndBack();
  TrajectoryFigureInput input;
  input.rows = &rows;
  const OccupancyGridImage grid = Grid();
  const GridTrajectoryFigure figure = TrajectoryOverGridFigure(input, grid, "t", 960, 800);
  EXPECT_DOUBLE_EQ(figure.width_px, 960.0);  // 200 × 100 cells: the width limits
  EXPECT_DOUBLE_EQ(figure.height_px, 480.0);
  EXPECT_NE(figure.svg.find("<image x=\"0\" y=\"0\" width=\"960\" height=\"480\""),
            std::string::npos);
  EXPECT_NE(figure.svg.find(GreyscalePngDataUri(200, 100, GridShades(grid))), std::string::npos);
  // The first posture, x = 0.123456 m, is (0.123456 + 1) m × 96 px/m from the left edge, kept to
  // a thousandth of a pixel (107.852 px), not snapped to a tenth.
  EXPECT_NE(figure.svg.find("points=\"107.852,240 136.652,240 "), std::string::npos);
  EXPECT_EQ(figure.legend.find("<image"), std::string::npos);  // the legend is apart
}

TEST(GridTrajectoryFigure, WhereThePathReturnsLabelsAreLeftOutRatherThanPiledUp) {
  const std::vector<IterationRow> rows = OutAndBack();
  TrajectoryFigureInput input;
  input.rows = &rows;
  for (std::size_t i = 0; i < rows.size(); ++i) input.linked.push_back(i);
  const GridTrajectoryFigure figure = TrajectoryOverGridFigure(input, Grid(), "t", 960, 800);
  const std::vector<Label> labels = Labels(figure.svg);
  // 10 places, each visited twice (the turn once): every ring drawn, about one label a place.
  std::size_t rings = 0;
  for (std::size_t at = figure.svg.find("<g class=\"marker\">"); at != std::string::npos;
       at = figure.svg.find("<g class=\"marker\">", at + 1))
    ++rings;
  EXPECT_EQ(rings, rows.size() + 2);  // every iteration, the start and the end
  EXPECT_GE(labels.size(), 10u);
  EXPECT_LT(labels.size(), rows.size() + 2);
  for (std::size_t i = 0; i < labels.size(); ++i)
    for (std::size_t j = 0; j < i; ++j) {
      const Label& a = labels[i];
      const Label& b = labels[j];
      EXPECT_FALSE(a.x0 < b.x1 - 0.01 && b.x0 < a.x1 - 0.01 && a.y0 < b.y1 - 0.01 &&
                   b.y0 < a.y1 - 0.01)
          << "labels " << i << " and " << j << " overlap";
    }
}

TEST(GridTrajectoryFigure, OccupiedCellsAreDarkFreeWhiteAndUnknownLightGrey) {
  OccupancyGridImage grid;
  grid.width = 3;
  grid.height = 1;
  grid.pixels = {kPgmOccupied, kPgmFree, kPgmUnknown};
  const std::vector<std::uint8_t> shades = GridShades(grid);
  EXPECT_LT(shades[0], 64);
  EXPECT_EQ(shades[1], 255);
  EXPECT_GT(shades[2], 200);
  EXPECT_LT(shades[2], 255);
}

}  // namespace
}  // namespace scanloc
