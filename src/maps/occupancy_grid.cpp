#include "scanloc/maps/occupancy_grid.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace scanloc {
namespace {

double ProbabilityOf(double log_odds) {
  // A cell never observed, most of a grid: exactly what the formula gives, without exp.
  if (log_odds == 0.0) return 0.5;
  return 1.0 - 1.0 / (1.0 + std::exp(log_odds));
}

// Calls visit(cell) for every cell a segment from `from` to `to` (in cell units) crosses before
// the cell of `to` (Amanatides & Woo's traversal), cell = y·width + x of a row-major grid.
template <typename Visit>
void TraverseCells(const Eigen::Vector2d& from, const Eigen::Vector2d& to, std::size_t width,
                   Visit&& visit) {
  const long x = static_cast<long>(std::floor(from.x())),
             y = static_cast<long>(std::floor(from.y()));
  const long end_x = static_cast<long>(std::floor(to.x()));
  const long end_y = static_cast<long>(std::floor(to.y()));
  const Eigen::Vector2d d = to - from;
  const long step_x = d.x() > 0 ? 1 : -1, step_y = d.y() > 0 ? 1 : -1;
  constexpr double kInfinity = std::numeric_limits<double>::infinity();
  const double delta_x = d.x() != 0.0 ? std::abs(1.0 / d.x()) : kInfinity;
  const double delta_y = d.y() != 0.0 ? std::abs(1.0 / d.y()) : kInfinity;
  double next_x =
      d.x() != 0.0 ? ((step_x > 0 ? x + 1 - from.x() : from.x() - x) * delta_x) : kInfinity;
  double next_y =
      d.y() != 0.0 ? ((step_y > 0 ? y + 1 - from.y() : from.y() - y) * delta_y) : kInfinity;
  // The cell index steps by ±1 along x and ±width along y (unsigned wrap-around adds the same).
  std::size_t cell = static_cast<std::size_t>(y) * width + static_cast<std::size_t>(x);
  const std::size_t cell_step_x = static_cast<std::size_t>(step_x);
  const std::size_t cell_step_y = static_cast<std::size_t>(step_y) * width;
  // At most one step per cell boundary between the two cells.
  const long steps = std::abs(end_x - x) + std::abs(end_y - y);
  for (long i = 0; i < steps; ++i) {
    visit(cell);
    if (next_x < next_y) {
      cell += cell_step_x;
      next_x += delta_x;
    } else {
      cell += cell_step_y;
      next_y += delta_y;
    }
  }
}

}  // namespace

void OccupancyGridOptions::Validate() const {
  auto fail = [](const std::string& what) {
    throw std::invalid_argument("OccupancyGridOptions: " + what);
  };
  if (!(resolution_m > 0.0) || !std::isfinite(resolution_m))
    fail("resolution_m must be positive, got " + std::to_string(resolution_m));
  if (!(log_odds_hit > 0.0)) fail("log_odds_hit must be positive");
  if (!(log_odds_miss < 0.0)) fail("log_odds_miss must be negative");
  if (!(log_odds_min < 0.0 && log_odds_max > 0.0)) fail("the log-odds clamp must include 0");
  if (!(free_probability >= 0.0 && free_probability < occupied_probability &&
        occupied_probability <= 1.0))
    fail("expected 0 <= free_probability < occupied_probability <= 1");
}

double OccupancyGrid::Probability(std::size_t x, std::size_t y) const {
  return ProbabilityOf(LogOdds(x, y));
}

CellState OccupancyGrid::State(std::size_t x, std::size_t y) const {
  const double p = Probability(x, y);
  if (p > occupied_probability) return CellState::kOccupied;
  if (p < free_probability) return CellState::kFree;
  return CellState::kUnknown;
}

bool OccupancyGrid::CellOf(const Eigen::Vector2d& point_m, std::size_t& x, std::size_t& y) const {
  const Eigen::Vector2d cell = (point_m - origin_m) / resolution_m;
  if (!(cell.x() >= 0.0 && cell.y() >= 0.0 && cell.x() < static_cast<double>(width) &&
        cell.y() < static_cast<double>(height)))
    return false;
  x = static_cast<std::size_t>(cell.x());
  y = static_cast<std::size_t>(cell.y());
  return true;
}

Eigen::Vector2d OccupancyGrid::CellCentre(std::size_t x, std::size_t y) const {
  return origin_m + resolution_m * Eigen::Vector2d(x + 0.5, y + 0.5);
}

OccupancyGridBuilder::OccupancyGridBuilder(OccupancyGridOptions options) : options_(options) {
  options_.Validate();
}

void OccupancyGridBuilder::AddScan(const LaserScan& scan, const Pose2D& T_world_laser) {
  scan.CheckConsistent();
  KeptScan kept{{}, T_world_laser};
  kept.scan.layout = scan.layout;
  kept.scan.ranges_m = scan.ranges_m;
  scans_.push_back(std::move(kept));
}

void OccupancyGridBuilder::MoveScan(std::size_t index, const Pose2D& T_world_laser) {
  scans_.at(index).T_world_laser = T_world_laser;
}

void OccupancyGridBuilder::EndPoints(const KeptScan& kept, std::vector<Eigen::Vector2d>& points) {
  points.clear();
  const BearingCosines& bearings = BearingCosinesOf(kept.scan.layout);
  const PoseTransform T_world_laser(kept.T_world_laser);
  for (std::size_t i = 0; i < kept.scan.size(); ++i) {
    if (!kept.scan.IsValid(i)) continue;
    const double r = kept.scan.ranges_m[i];
    points.push_back(T_world_laser({r * bearings.cos[i], r * bearings.sin[i]}));
  }
}

OccupancyGrid OccupancyGridBuilder::Build() const {
  OccupancyGrid grid;
  grid.resolution_m = options_.resolution_m;
  grid.occupied_probability = options_.occupied_probability;
  grid.free_probability = options_.free_probability;
  if (scans_.empty()) return grid;
  Eigen::Vector2d low = scans_.front().T_world_laser.Translation(), high = low;
  std::vector<Eigen::Vector2d> endpoints;
  for (const KeptScan& kept : scans_) {
    EndPoints(kept, endpoints);
    endpoints.push_back(kept.T_world_laser.Translation());
    for (const Eigen::Vector2d& p : endpoints) {
      low = low.cwiseMin(p);
      high = high.cwiseMax(p);
    }
  }
  const double r = options_.resolution_m;
  const double margin = static_cast<double>(options_.margin_cells);
  // Cell corners on multiples of the resolution, so that grids of one place line up.
  grid.origin_m = ((low / r).array().floor() - margin).matrix() * r;
  grid.width =
      static_cast<std::size_t>(std::floor((high.x() - grid.origin_m.x()) / r) + 1 + margin);
  grid.height =
      static_cast<std::size_t>(std::floor((high.y() - grid.origin_m.y()) / r) + 1 + margin);

  // Each scan votes once per cell: a cell where one of its beams ends, or else one they cross.
  // The end cells are marked first, so that a crossed cell is voted free as it is first crossed.
  // A cell's marks and log-odds side by side: a traversal step reads one place in memory.
  struct Votes {
    std::uint32_t missed = 0, hit = 0;  // the last scan that crossed it, that ended in it
    float log_odds = 0.0f;
  };
  std::vector<Votes> votes(grid.width * grid.height);
  const double lowest = options_.log_odds_min, highest = options_.log_odds_max;
  auto update = [&](Votes& cell, double change) {
    cell.log_odds = static_cast<float>(std::clamp(cell.log_odds + change, lowest, highest));
  };
  const double miss = options_.log_odds_miss, hit = options_.log_odds_hit;
  std::vector<std::size_t> ends;  // one scan's end cells, in beam order
  for (std::size_t s = 0; s < scans_.size(); ++s) {
    const std::uint32_t mark = static_cast<std::uint32_t>(s + 1);
    const Eigen::Vector2d from = (scans_[s].T_world_laser.Translation() - grid.origin_m) / r;
    EndPoints(scans_[s], endpoints);
    ends.clear();
    for (const Eigen::Vector2d& endpoint : endpoints) {
      const Eigen::Vector2d to = (endpoint - grid.origin_m) / r;
      ends.push_back(static_cast<std::size_t>(to.y()) * grid.width +
                     static_cast<std::size_t>(to.x()));
      votes[ends.back()].hit = mark;
    }
    for (const Eigen::Vector2d& endpoint : endpoints)
      TraverseCells(from, (endpoint - grid.origin_m) / r, grid.width, [&](std::size_t cell) {
        Votes& crossed = votes[cell];
        if (crossed.missed == mark) return;
        crossed.missed = mark;
        if (crossed.hit != mark) update(crossed, miss);
      });
    for (const std::size_t cell : ends)
      if (votes[cell].hit == mark) {
        update(votes[cell], hit);
        votes[cell].hit = 0;  // counted once
      }
  }
  grid.log_odds.resize(votes.size());
  for (std::size_t cell = 0; cell < votes.size(); ++cell)
    grid.log_odds[cell] = votes[cell].log_odds;
  return grid;
}

}  // namespace scanloc
