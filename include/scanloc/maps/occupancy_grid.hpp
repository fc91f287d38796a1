#pragma once
// A log-odds occupancy grid built from scans at known postures: each valid beam marks the cells it
// crosses as free and the cell of its end point as occupied (inverse sensor model of Thrun et al.,
// Probabilistic Robotics §9.2); beams without an echo are ignored.

#include <Eigen/Core>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/geometry/pose2d.hpp"

namespace scanloc {

struct OccupancyGridOptions {
  double resolution_m = 0.05;   // cell side, metres (> 0)
  double log_odds_hit = 0.85;   // added where a beam ends: ln(0.7 / 0.3)
  double log_odds_miss = -0.2;  // added to each cell a beam crosses: ln(0.45 / 0.55); a hit
  // outweighs four misses, so that walls seen at grazing incidence from afar are not cleared (on
  // ACES −0.4 left 82 % of the map points on occupied cells, −0.2 89 %)
  double log_odds_min = -2.0;          // clamp, so that a wall seen again after a while returns
  double log_odds_max = 3.5;           // clamp
  double occupied_probability = 0.65;  // above: occupied (map_server's occupied_thresh)
  double free_probability = 0.196;     // below: free (map_server's free_thresh)
  std::size_t margin_cells = 2;        // unknown cells around what was observed
  // Throws std::invalid_argument for a non-positive resolution, a hit <= 0, a miss >= 0, a clamp
  // that excludes 0, or thresholds outside 0 <= free < occupied <= 1.
  void Validate() const;
};

enum class CellState : std::uint8_t { kUnknown, kFree, kOccupied };

struct OccupancyGrid {
  double resolution_m = 0.05;
  Eigen::Vector2d origin_m = Eigen::Vector2d::Zero();  // world position of cell (0, 0)'s corner
  std::size_t width = 0;                               // cells along x
  std::size_t height = 0;                              // cells along y
  std::vector<float> log_odds;                         // row-major, row 0 at the lowest y
  double occupied_probability = 0.65;
  double free_probability = 0.196;

  float LogOdds(std::size_t x, std::size_t y) const { return log_odds[y * width + x]; }
  double Probability(std::size_t x, std::size_t y) const;
  CellState State(std::size_t x, std::size_t y) const;
  // The cell holding a world point; false when outside the grid.
  bool CellOf(const Eigen::Vector2d& point_m, std::size_t& x, std::size_t& y) const;
  Eigen::Vector2d CellCentre(std::size_t x, std::size_t y) const;
};

// Collects scans at their laser postures, then builds the grid over everything they observed.
class OccupancyGridBuilder {
 public:
  explicit OccupancyGridBuilder(OccupancyGridOptions options = {});
  OccupancyGridBuilder(const OccupancyGridBuilder&) = delete;
  OccupancyGridBuilder& operator=(const OccupancyGridBuilder&) = delete;
  OccupancyGridBuilder(OccupancyGridBuilder&&) = default;

  // Keeps the scan's ranges and T_world_laser; its valid beams become rays from the laser to
  // their end points.
  void AddScan(const LaserScan& scan, const Pose2D& T_world_laser);
  std::size_t scans() const { return scans_.size(); }
  // The `index`-th scan kept (in the order added) lies at `T_world_laser` instead: a posture
  // corrected after the fact (loop closure). Throws std::out_of_range for an index not kept.
  void MoveScan(std::size_t index, const Pose2D& T_world_laser);
  // Casts every ray, scan by scan (misses first, then the scan's hits). An empty builder gives an
  // empty grid (width = height = 0).
  OccupancyGrid Build() const;

 private:
  struct KeptScan {
    LaserScan scan;  // layout and ranges only: 8 bytes a beam, half a world end point's 16
    Pose2D T_world_laser;
  };
  // The world end points of the scan's valid beams.
  static void EndPoints(const KeptScan& kept, std::vector<Eigen::Vector2d>& points);

  OccupancyGridOptions options_;
  std::vector<KeptScan> scans_;
};

}  // namespace scanloc
