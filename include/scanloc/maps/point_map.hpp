#pragma once
// The point map: world points accumulated from localised scans (3.6) or sampled from a line map,
// with a k-d tree that grows incrementally, a de-duplication grid so that the map grows with the
// explored area rather than with the number of scans, and coarse blocks for searches that cull
// whole regions (the simulated scan, free-space carving).

#include <Eigen/Core>
#include <cstdint>
#include <functional>
#include <memory>
#include <utility>
#include <vector>

#include "scanloc/geometry/laser_scan.hpp"
#include "scanloc/geometry/pose2d.hpp"

namespace scanloc {

struct PointMapOptions {
  // De-duplication: a point is not inserted when its square cell of this side already holds one.
  // 0 disables de-duplication. Metres.
  double cell_size_m = 0.05;
  // Upper bound of the spacing recorded with a point (the gap to its neighbours on the surface it
  // samples); it bounds how much of the view one isolated point may occlude. Metres.
  double max_point_spacing_m = 0.3;

  friend bool operator==(const PointMapOptions& a, const PointMapOptions& b) {
    return a.cell_size_m == b.cell_size_m && a.max_point_spacing_m == b.max_point_spacing_m;
  }
  friend bool operator!=(const PointMapOptions& a, const PointMapOptions& b) { return !(a == b); }
};

class PointMap {
 public:
  explicit PointMap(PointMapOptions options = {});
  ~PointMap();
  PointMap(PointMap&&) noexcept;
  PointMap& operator=(PointMap&&) noexcept;
  PointMap(const PointMap&) = delete;
  PointMap& operator=(const PointMap&) = delete;

  // Inserts one point sampling a surface with the given local spacing. De-duplication: when an
  // existing point's first sample lies within one cell diagonal (cell_size_m·√2), the sample is
  // merged into the nearest such point, which becomes the mean of its samples (normal: the mean
  // normal; spacing: the smaller), and false is returned. Repeated noisy scans of a wall then
  // average out into one layer of points instead of piling up in front of it.
  bool Insert(const Eigen::Vector2d& point_world, double spacing_m);
  // Inserts many points at once (one index update); returns how many were added. `normals_world`
  // is empty (unknown) or holds one unit normal of the sampled surface per point (zero: unknown).
  std::size_t Insert(const std::vector<Eigen::Vector2d>& points_world,
                     const std::vector<double>& spacings_m,
                     const std::vector<Eigen::Vector2d>& normals_world = {});
  // Adds points as they are, merging none (their cells are registered for later samples): how a
  // saved map is restored point for point. Returns how many were added (non-finite ones are not).
  std::size_t Restore(const std::vector<Eigen::Vector2d>& points_world,
                      const std::vector<double>& spacings_m,
                      const std::vector<Eigen::Vector2d>& normals_world = {});
  // (3.6) Inserts the valid beams of a scan taken from T_world_laser; each point's spacing is the
  // distance to its nearest valid neighbouring beam (r·Δθ when it has none) and its normal is
  // perpendicular to the line through its neighbouring beams' points (unknown at depth jumps).
  // Returns points added.
  std::size_t InsertScan(const LaserScan& scan, const Pose2D& T_world_laser);
  // Free-space carving: every point that the beams of this scan (taken from T_world_laser) saw
  // through, lying more than margin_m + margin_per_m·r in front of the nearest return r of its
  // beam and both neighbouring beams, gets a miss; a point seen through more often than it was
  // seen (misses > samples) is removed: people, doors and other things that moved do not stay in
  // the map to occlude it. Beams without an echo carve nothing (glass, black surfaces). Returns
  // the points removed. The margins have no default here: SessionOptions::free_space_margin_m
  // and free_space_margin_per_m are their one declaration.
  // Points with an index below first_index are left as they are: a scan carving the points laid
  // after it (LoopCloser::Render's second pass) passes the map's size after its own insertion.
  std::size_t CarveFreeSpace(const LaserScan& scan, const Pose2D& T_world_laser, double margin_m,
                             double margin_per_m, std::uint32_t first_index = 0);

  // Slots: indices 0 … size()−1 address points, some of which may have been removed by carving
  // (alive(i) false): they are in no search result and no saved map.
  std::size_t size() const;
  std::size_t live_size() const;
  bool alive(std::size_t i) const;
  bool empty() const { return live_size() == 0; }
  const Eigen::Vector2d& point(std::size_t i) const;
  double spacing(std::size_t i) const;
  // The unit normal of the surface point i samples, or zero when unknown.
  Eigen::Vector2d normal(std::size_t i) const;
  const PointMapOptions& options() const { return options_; }

  // Indices of points within radius_m of the centre, with squared distances (unsorted). Exact
  // with respect to point(i), the cell means.
  std::vector<std::pair<std::uint32_t, double>> RadiusSearch(const Eigen::Vector2d& centre,
                                                             double radius_m) const;
  // The same into `found` (cleared first), whose capacity is reused: hot loops (simulated scans,
  // line fits) search thousands of times per scan and need not allocate each time.
  void RadiusSearch(const Eigen::Vector2d& centre, double radius_m,
                    std::vector<std::pair<std::uint32_t, double>>& found) const;
  // The k nearest points, nearest first, with squared distances (exact, as RadiusSearch).
  std::vector<std::pair<std::uint32_t, double>> KNearest(const Eigen::Vector2d& centre,
                                                         std::size_t k) const;

  // Coarse blocks, for searches that cull whole regions at once (the simulated scan skips the
  // blocks its beams cannot see). Block (ix, iy) lists the slots, dead ones included, whose first
  // sample lies in [ix·s, (ix+1)·s) × [iy·s, (iy+1)·s) with s = kBlockSideM; their means lie within
  // block_margin_m() of that square. Block returns nullptr for a block that holds none.
  static constexpr double kBlockSideM = 2.0;
  struct BlockRange {
    std::int64_t x0 = 0, x1 = -1, y0 = 0, y1 = -1;  // inclusive; empty when x1 < x0
  };
  static std::int64_t BlockIndex(double coordinate_m);
  const std::vector<std::uint32_t>* Block(std::int64_t ix, std::int64_t iy) const;
  double block_margin_m() const { return MaxIndexDisplacement(); }
  // The blocks spanned by every point ever added.
  BlockRange block_range() const;
  // RadiusSearch's points with an index from first_index on that lie in the blocks
  // keep_block(ix, iy) accepts (the carving keeps the blocks a scan saw through), in no
  // particular order. A block's slots are in the order the points were added: a block holding
  // none from first_index on is skipped whole.
  void RadiusSearchInBlocks(const Eigen::Vector2d& centre, double radius_m,
                            const std::function<bool(std::int64_t, std::int64_t)>& keep_block,
                            std::vector<std::pair<std::uint32_t, double>>& found,
                            std::uint32_t first_index = 0) const;

 private:
  // How far a cell mean may lie from the first sample the k-d tree indexes (one cell diagonal).
  double MaxIndexDisplacement() const;
  std::size_t Add(const std::vector<Eigen::Vector2d>& points_world,
                  const std::vector<double>& spacings_m,
                  const std::vector<Eigen::Vector2d>& normals_world, bool merge);
  struct Storage;
  PointMapOptions options_;
  std::unique_ptr<Storage> storage_;
};

// Builds a point map from a line map sampled every spacing_m (§3.2.2, vertices included).
struct LineMap;
PointMap PointMapFromLines(const LineMap& lines, double spacing_m = 0.0075,
                           PointMapOptions options = {});

}  // namespace scanloc
