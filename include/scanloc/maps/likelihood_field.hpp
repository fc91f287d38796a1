#pragma once
// A likelihood field over a map: a grid whose cells hold exp(−d²/2σ²) of the distance d from the
// cell's centre to the nearest map point (0 beyond 3σ), and coarser levels whose cells hold the
// maximum over a block of 2^h × 2^h finer cells starting at them: the upper bounds a branch and
// bound search over translations needs (Olson 2009; Hess et al. 2016). Values are held as whole
// 255ths in a byte, as Cartographer holds its grids: a search reads the levels at scattered cells,
// and a byte a cell keeps four times as many of them in the cache as a float did (a global search
// on ACES's map ran 1.3–2× faster, docs/BENCHMARKS.md). Sums of quanta are exact, so a block's
// bound stays the exact maximum of what its postures score.

#include <Eigen/Core>
#include <array>
#include <cstddef>
#include <cstdint>
#include <cstdlib>
#include <stdexcept>
#include <vector>

namespace scanloc {

struct LikelihoodFieldOptions {
  double resolution_m = 0.05;  // side of a cell, metres
  double sigma_m = 0.1;        // σ of the field around each point, metres
  int levels = 6;              // levels 0 (the field) … levels − 1 (blocks of 2^(levels−1))
  // Throws std::invalid_argument naming the first option out of its domain.
  void Validate() const;
};

class LikelihoodField {
 public:
  static constexpr float kQuantum = 1.0f / 255.0f;  // the step of the values held
  // The field of `points` over the square cells covering [min_world, max_world].
  LikelihoodField(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& min_world,
                  const Eigen::Vector2d& max_world, const LikelihoodFieldOptions& options = {});
  // An empty field: no cell, 0 everywhere, until Rebuild.
  LikelihoodField() = default;
  // The field of other points over another box, in the storage this one holds: a caller that
  // builds many fields of like size (a search per closure attempt) reuses the same pages
  // instead of asking the system for fresh ones each time. Throws as the constructor does.
  void Rebuild(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& min_world,
               const Eigen::Vector2d& max_world, const LikelihoodFieldOptions& options = {});

  // Level h's value of cell (ix, iy); 0 outside the grid.
  float At(int level, int ix, int iy) const {
    if (ix < 0 || iy < 0 || ix >= width_ || iy >= height_) return 0.0f;
    return levels_[level][static_cast<std::size_t>(iy) * width_ + ix] * kQuantum;
  }
  // The sum of level h's values over `cells`, each moved by (dx, dy): the score of a posture, read
  // in one pass over one level (cells outside the grid add 0), added exactly as whole quanta.
  float Sum(int level, const std::vector<Eigen::Vector2i>& cells, int dx, int dy) const {
    return static_cast<float>(CheckedQuanta(levels_[level].data(), cells, dx, dy)) * kQuantum;
  }
  // Cells to be summed at every move (dx, dy) with |dx|, |dy| <= reach: those inside the grid
  // for every such move as offsets into it (y·width + x, read without a bounds test), the rest as
  // they are. A search sums one scan's cells at many moves; most of them never leave the grid.
  struct MovedCells {
    int reach = 0;
    std::vector<std::int32_t> inside;
    std::vector<Eigen::Vector2i> edge;
    std::size_t size() const { return inside.size() + edge.size(); }
  };
  MovedCells Split(const std::vector<Eigen::Vector2i>& cells, int reach) const;
  // Sum's total for split cells, in quanta (the same whole number for the same cells and move).
  unsigned SumQuanta(int level, const MovedCells& cells, int dx, int dy) const {
    if (std::abs(dx) > cells.reach || std::abs(dy) > cells.reach)
      throw std::out_of_range("LikelihoodField::SumQuanta: a move beyond the cells' reach");
    const std::uint8_t* values = levels_[level].data();
    const std::ptrdiff_t offset = static_cast<std::ptrdiff_t>(dy) * width_ + dx;
    unsigned sum = 0;
    for (const std::int32_t index : cells.inside) sum += values[index + offset];
    return sum + CheckedQuanta(values, cells.edge, dx, dy);
  }
  // SumQuanta at the four moves (dx, dy), (dx + step, dy), (dx, dy + step) and
  // (dx + step, dy + step), in that order, in one pass over the cells: a branch and bound node's
  // four children read neighbouring bytes of each cell's row, so one pass keeps four sums going
  // where four passes waited on memory four times. Each total is SumQuanta's; every move must
  // lie within the cells' reach.
  std::array<unsigned, 4> SumQuantaOfFour(int level, const MovedCells& cells, int dx, int dy,
                                          int step) const;
  // The cell holding a world point (may lie outside the grid).
  Eigen::Vector2i Cell(const Eigen::Vector2d& world) const;
  int levels() const { return static_cast<int>(levels_.size()); }
  int width() const { return width_; }
  int height() const { return height_; }
  double resolution_m() const { return resolution_m_; }

 private:
  // The quanta of `values` (one level) over `cells` moved by (dx, dy), each tested against the
  // grid's bounds (cells outside add 0).
  unsigned CheckedQuanta(const std::uint8_t* values, const std::vector<Eigen::Vector2i>& cells,
                         int dx, int dy) const {
    unsigned sum = 0;
    for (const Eigen::Vector2i& c : cells) {
      const int ix = c.x() + dx, iy = c.y() + dy;
      if (static_cast<unsigned>(ix) < static_cast<unsigned>(width_) &&
          static_cast<unsigned>(iy) < static_cast<unsigned>(height_))
        sum += values[static_cast<std::size_t>(iy) * width_ + ix];
    }
    return sum;
  }
  void Splat(const Eigen::Vector2d& point, double sigma_m);
  void BuildLevel(int level);

  Eigen::Vector2d origin_world_ = Eigen::Vector2d::Zero();  // the corner of cell (0, 0)
  double resolution_m_ = 1.0;
  int width_ = 0, height_ = 0;
  std::vector<std::vector<std::uint8_t>> levels_;
  std::vector<double> columns_;  // Splat's Gaussian per column, kept to save an allocation
};

}  // namespace scanloc
