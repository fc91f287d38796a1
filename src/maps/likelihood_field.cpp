#include "scanloc/maps/likelihood_field.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace scanloc {
namespace {

// The field is cut at this many σ (exp(−4.5) ≈ 0.011).
constexpr double kCutoffSigmas = 3.0;
// A grid larger than this many cells is refused (64 MB a level).
constexpr double kMaxCells = 6.4e7;

}  // namespace

void LikelihoodFieldOptions::Validate() const {
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("LikelihoodFieldOptions: ") + what);
  };
  require(std::isfinite(resolution_m) && resolution_m > 0.0, "resolution_m must be positive");
  require(std::isfinite(sigma_m) && sigma_m > 0.0, "sigma_m must be positive");
  require(levels >= 1 && levels <= 16, "levels must be in [1, 16]");
}

LikelihoodField::LikelihoodField(const std::vector<Eigen::Vector2d>& points,
                                 const Eigen::Vector2d& min_world, const Eigen::Vector2d& max_world,
                                 const LikelihoodFieldOptions& options) {
  Rebuild(points, min_world, max_world, options);
}

void LikelihoodField::Rebuild(const std::vector<Eigen::Vector2d>& points,
                              const Eigen::Vector2d& min_world, const Eigen::Vector2d& max_world,
                              const LikelihoodFieldOptions& options) {
  options.Validate();
  if (!(max_world.array() >= min_world.array()).all() || !min_world.allFinite() ||
      !max_world.allFinite())
    throw std::invalid_argument("LikelihoodField: the box's corners must be finite and ordered");
  const Eigen::Vector2d cells = (max_world - min_world) / options.resolution_m;
  if ((cells.x() + 1.0) * (cells.y() + 1.0) > kMaxCells)
    throw std::invalid_argument("LikelihoodField: the box needs more than 6.4e7 cells");
  origin_world_ = min_world;
  resolution_m_ = options.resolution_m;
  width_ = static_cast<int>(std::ceil(cells.x())) + 1;
  height_ = static_cast<int>(std::ceil(cells.y())) + 1;
  levels_.resize(static_cast<std::size_t>(options.levels));
  levels_[0].assign(static_cast<std::size_t>(width_) * height_, 0);
  for (const Eigen::Vector2d& p : points) Splat(p, options.sigma_m);
  for (int h = 1; h < options.levels; ++h) BuildLevel(h);
}

Eigen::Vector2i LikelihoodField::Cell(const Eigen::Vector2d& world) const {
  const Eigen::Vector2d c = (world - origin_world_) / resolution_m_;
  return {static_cast<int>(std::floor(c.x())), static_cast<int>(std::floor(c.y()))};
}

LikelihoodField::MovedCells LikelihoodField::Split(const std::vector<Eigen::Vector2i>& cells,
                                                   int reach) const {
  if (reach < 0) throw std::invalid_argument("LikelihoodField::Split: reach must be >= 0");
  MovedCells split;
  split.reach = reach;
  for (const Eigen::Vector2i& c : cells) {
    const bool inside = c.x() - reach >= 0 && c.x() + reach < width_ && c.y() - reach >= 0 &&
                        c.y() + reach < height_;
    if (inside)
      split.inside.push_back(c.y() * width_ + c.x());
    else
      split.edge.push_back(c);
  }
  return split;
}

std::array<unsigned, 4> LikelihoodField::SumQuantaOfFour(int level, const MovedCells& cells, int dx,
                                                         int dy, int step) const {
  if (step < 0 || std::min(dx, dy) < -cells.reach || std::max(dx, dy) + step > cells.reach)
    throw std::out_of_range("LikelihoodField::SumQuantaOfFour: a move beyond the cells' reach");
  const std::uint8_t* values = levels_[level].data();
  const std::ptrdiff_t offset = static_cast<std::ptrdiff_t>(dy) * width_ + dx;
  const std::ptrdiff_t up = static_cast<std::ptrdiff_t>(step) * width_;
  unsigned s00 = 0, s10 = 0, s01 = 0, s11 = 0;
  for (const std::int32_t index : cells.inside) {
    const std::uint8_t* at = values + index + offset;
    s00 += at[0];
    s10 += at[step];
    s01 += at[up];
    s11 += at[up + step];
  }
  return {s00 + CheckedQuanta(values, cells.edge, dx, dy),
          s10 + CheckedQuanta(values, cells.edge, dx + step, dy),
          s01 + CheckedQuanta(values, cells.edge, dx, dy + step),
          s11 + CheckedQuanta(values, cells.edge, dx + step, dy + step)};
}

// Raises the cells within kCutoffSigmas·σ of the point (a square of them) to exp(−d²/2σ²) of their
// centre's distance, rounded to the nearest quantum. The Gaussian is separable: one exp per
// column and one per row, where a cell by cell exp made building a field a tenth of a loop-closing
// session. A row whose largest value rounds to 0 changes no cell and is skipped.
void LikelihoodField::Splat(const Eigen::Vector2d& point, double sigma_m) {
  const int reach = static_cast<int>(std::ceil(kCutoffSigmas * sigma_m / resolution_m_));
  const Eigen::Vector2i centre = Cell(point);
  const int x0 = std::max(0, centre.x() - reach), x1 = std::min(width_ - 1, centre.x() + reach);
  const int y0 = std::max(0, centre.y() - reach), y1 = std::min(height_ - 1, centre.y() + reach);
  if (x0 > x1 || y0 > y1) return;
  const double inv_two_sigma2 = 1.0 / (2.0 * sigma_m * sigma_m);
  auto gaussian = [&](int index, double origin, double coordinate) {
    const double d = origin + resolution_m_ * (index + 0.5) - coordinate;
    return std::exp(-(d * d) * inv_two_sigma2);
  };
  columns_.clear();
  for (int ix = x0; ix <= x1; ++ix) columns_.push_back(gaussian(ix, origin_world_.x(), point.x()));
  std::vector<std::uint8_t>& field = levels_[0];
  for (int iy = y0; iy <= y1; ++iy) {
    const double row = 255.0 * gaussian(iy, origin_world_.y(), point.y());
    if (row < 0.5) continue;
    std::uint8_t* cells = field.data() + static_cast<std::size_t>(iy) * width_;
    for (int ix = x0; ix <= x1; ++ix) {
      // Rounded to the nearest quantum, halves up, as lround for these values in [0, 255]
      // (below 0.5 the sum v + 0.5 could round up to 1, so those are 0 outright).
      const double v = row * columns_[ix - x0];
      const auto value = static_cast<std::uint8_t>(v < 0.5 ? 0 : static_cast<int>(v + 0.5));
      cells[ix] = std::max(cells[ix], value);
    }
  }
}

// Level h's cell (x, y) = the maximum of level h−1 over (x, y), (x+s, y), (x, y+s), (x+s, y+s),
// s = 2^(h−1): the maximum over the 2^h × 2^h block of the field starting at (x, y). Taken along
// rows, then along columns; cells beyond the grid hold 0 and every value is at least 0, so a
// neighbour beyond it leaves the cell's own value.
void LikelihoodField::BuildLevel(int level) {
  const std::size_t step = std::size_t{1} << (level - 1);
  const std::size_t width = static_cast<std::size_t>(width_);
  const std::size_t height = static_cast<std::size_t>(height_);
  std::vector<std::uint8_t>& values = levels_[static_cast<std::size_t>(level)];
  values = levels_[static_cast<std::size_t>(level) - 1];
  for (std::size_t iy = 0; iy < height; ++iy) {
    std::uint8_t* row = values.data() + iy * width;
    for (std::size_t ix = 0; ix + step < width; ++ix) row[ix] = std::max(row[ix], row[ix + step]);
  }
  for (std::size_t iy = 0; iy + step < height; ++iy) {
    std::uint8_t* row = values.data() + iy * width;
    const std::uint8_t* below = row + step * width;
    for (std::size_t ix = 0; ix < width; ++ix) row[ix] = std::max(row[ix], below[ix]);
  }
}

}  // namespace scanloc
