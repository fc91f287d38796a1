#include "scanloc/maps/point_map.hpp"

#include "scanloc/geometry/approximate_bearing.hpp"

#include <algorithm>
#include <cmath>
#include <optional>
#include <stdexcept>
#include <unordered_map>

#include <Eigen/Geometry>

// nanoflann 1.4 trips -Wmaybe-uninitialized in its own header when optimised.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <nanoflann.hpp>
#pragma GCC diagnostic pop

#include "cell_table.hpp"
#include "cell_tiles.hpp"
#include "scanloc/maps/line_map.hpp"

namespace scanloc {
namespace {

// nanoflann's view of the point storage.
struct CloudAdaptor {
  const std::vector<Eigen::Vector2d>* points;
  std::size_t kdtree_get_point_count() const { return points->size(); }
  double kdtree_get_pt(std::size_t i, std::size_t dim) const { return (*points)[i][dim]; }
  template <class BoundingBox>
  bool kdtree_get_bbox(BoundingBox&) const {
    return false;
  }
};

using KdTree =
    nanoflann::KDTreeSingleIndexDynamicAdaptor<nanoflann::L2_Simple_Adaptor<double, CloudAdaptor>,
                                               CloudAdaptor, 2, std::uint32_t>;

// Cell indices are clamped to ±2^62 (and NaN goes to 0) so that the conversion to an integer is
// defined for any coordinate; readers refuse coordinates beyond kMaxCoordinateM long before that.
std::int64_t CellIndex(double coordinate, double cell_size_m) {
  constexpr double kMaxCellIndex = 4611686018427387904.0;  // 2^62
  const double index = std::floor(coordinate / cell_size_m);
  if (!(std::abs(index) < kMaxCellIndex))
    return index > 0.0 ? (1LL << 62) : index < 0.0 ? -(1LL << 62) : 0;
  return static_cast<std::int64_t>(index);
}

std::int64_t CellKey(std::int64_t ix, std::int64_t iy) {
  // Unsigned shift: the same bits as ix << 32, without shifting a negative number.
  return static_cast<std::int64_t>((static_cast<std::uint64_t>(ix) << 32) ^
                                   (static_cast<std::uint64_t>(iy) & 0xffffffffULL));
}

std::int64_t CellKey(const Eigen::Vector2d& p, double cell_size_m) {
  return CellKey(CellIndex(p.x(), cell_size_m), CellIndex(p.y(), cell_size_m));
}

// The point held by one of the 3×3 cells around `p` whose first sample is nearest it: within one
// cell diagonal, or anywhere in p's own cell; kNone if none. The cells' indices are those of p
// moved by a cell each way (six divisions, not eighteen: each is needed thrice).
std::uint32_t NearestHeld(const CellTiles& cells, const std::vector<Eigen::Vector2d>& first_samples,
                          const Eigen::Vector2d& p, double c) {
  std::int64_t ix[3], iy[3];
  for (int k = 0; k < 3; ++k) {
    ix[k] = CellIndex(p.x() + (k - 1) * c, c);
    iy[k] = CellIndex(p.y() + (k - 1) * c, c);
  }
  std::uint32_t held[3][3];
  cells.FindNine(ix, iy, held);
  const double reach2 = 2.0 * c * c;
  double nearest2 = std::numeric_limits<double>::infinity();
  std::uint32_t nearest = CellTiles::kNone;
  for (int dx = 0; dx < 3; ++dx)
    for (int dy = 0; dy < 3; ++dy) {
      if (held[dx][dy] == CellTiles::kNone) continue;
      const double d2 = (first_samples[held[dx][dy]] - p).squaredNorm();
      if (d2 < nearest2 && (d2 < reach2 || (dx == 1 && dy == 1))) {
        nearest2 = d2;
        nearest = held[dx][dy];
      }
    }
  return nearest;
}

// Removes `index` from a list of point indices, keeping the others' order.
void EraseIndex(std::vector<std::uint32_t>& indices, std::uint32_t index) {
  const auto found = std::find(indices.begin(), indices.end(), index);
  if (found != indices.end()) indices.erase(found);
}

// Side of the search grid's cells. Short searches (the refinement's line fits: 0.3 m, several
// thousand per scan) visit the few cells they overlap instead of the dynamic k-d tree's
// sub-trees; longer ones use the tree.
constexpr double kSearchCellM = 0.5;
constexpr std::int64_t kMaxSearchCells = 16;

// Which blocks a scan's carving must look into: those holding a point that may lie in front of
// the return of the beam it falls in (CarveFreeSpace's test, bounded over the block).
struct CarvedBlocks {
  const Pose2D& T_world_laser;
  const ScanLayout& layout;
  const std::vector<double>& nearest;  // per beam, the nearest return of it and its neighbours
  double margin_m, margin_per_m, block_margin_m;

  bool MayHoldCarved(std::int64_t ix, std::int64_t iy) const {
    const double side = PointMap::kBlockSideM;
    const Eigen::Vector2d centre((static_cast<double>(ix) + 0.5) * side,
                                 (static_cast<double>(iy) + 0.5) * side);
    const double radius = side * M_SQRT1_2 + block_margin_m;  // a disc holding the block's means
    const Eigen::Vector2d delta = centre - T_world_laser.Translation();
    const double centre_distance = delta.norm();
    const double closest = centre_distance - radius - 1e-9;
    if (closest <= layout.range_min_m) return true;  // beside the laser: look
    // Each point falls in the beam nearest its bearing, within half a step of the disc's span.
    const double half = std::asin(radius / centre_distance) + layout.angle_increment_rad;
    if (half >= 0.5 * M_PI) return true;
    const double bearing = std::atan2(delta.y(), delta.x()) - T_world_laser.yaw_rad;
    return AnyBeamInInterval(layout, bearing - half, 2.0 * half, [&](std::size_t beam) {
      const double hit = nearest[beam];
      return hit >= 0.0 && closest < hit - margin_m - margin_per_m * hit;
    });
  }
};

}  // namespace

// A cell's point is the running mean of the samples that fell in it, so that the noise of many
// scans averages out instead of piling up (the nearest of a thick noisy cloud would bias every
// simulated range short). The k-d tree keeps each point's first sample (`indexed`), which stays
// within one cell diagonal of the mean: searches widen by that margin and filter on the means.
constexpr int kMaxMergedSamples = 50;  // then a moving average: the map still follows changes

struct PointMap::Storage {
  std::vector<Eigen::Vector2d> points;   // cell means
  std::vector<Eigen::Vector2d> indexed;  // first samples, what the k-d tree holds
  std::vector<double> spacings;
  std::vector<Eigen::Vector2f> normals;  // float: normals need no more, and maps can be large
  std::vector<std::uint16_t> samples;    // samples merged into each point (capped)
  std::vector<std::uint16_t> misses;     // scans that saw through the point (carving)
  std::vector<std::uint8_t> alive;       // 0 once carving removed the point
  std::size_t removed = 0;
  // Bounds of `indexed`, every point ever added: a search whose radius covers them lists the
  // live points directly instead of walking the tree to every leaf.
  Eigen::AlignedBox2d bounds;
  CellTiles occupied_cells;
  // The live points by the kSearchCellM cell of their first sample, in the order they were added
  // (carving takes a point out of its cell and its block): the cell's key gives the index of its
  // list (a CellTable probe, not std::unordered_map's division and node pointer).
  CellTable search_cell_of;
  std::vector<std::vector<std::uint32_t>> search_cells;
  std::vector<std::uint32_t>* SearchCell(std::int64_t key) {
    const std::uint32_t list = search_cell_of.Find(key);
    return list == CellTable::kNone ? nullptr : &search_cells[list];
  }
  // The same by kBlockSideM block, for region culling.
  struct Block {
    std::int64_t ix, iy;
    std::vector<std::uint32_t> slots;
  };
  std::unordered_map<std::int64_t, Block> blocks;
  CloudAdaptor adaptor{&indexed};
  KdTree tree{2, adaptor, nanoflann::KDTreeSingleIndexAdaptorParams(16)};
};

PointMap::PointMap(PointMapOptions options)
    : options_(options), storage_(std::make_unique<Storage>()) {
  if (!(options_.cell_size_m >= 0.0) || !std::isfinite(options_.cell_size_m))
    throw std::invalid_argument("PointMapOptions: cell_size_m must be finite and >= 0");
  if (!(options_.max_point_spacing_m > 0.0) || !std::isfinite(options_.max_point_spacing_m))
    throw std::invalid_argument("PointMapOptions: max_point_spacing_m must be finite and > 0");
}
PointMap::~PointMap() = default;
PointMap::PointMap(PointMap&&) noexcept = default;
PointMap& PointMap::operator=(PointMap&&) noexcept = default;

std::size_t PointMap::size() const {
  return storage_->points.size();
}
std::size_t PointMap::live_size() const {
  return storage_->points.size() - storage_->removed;
}
bool PointMap::alive(std::size_t i) const {
  return storage_->alive[i] != 0;
}
const Eigen::Vector2d& PointMap::point(std::size_t i) const {
  return storage_->points[i];
}
double PointMap::spacing(std::size_t i) const {
  return storage_->spacings[i];
}
Eigen::Vector2d PointMap::normal(std::size_t i) const {
  return storage_->normals[i].cast<double>();
}

std::size_t PointMap::Insert(const std::vector<Eigen::Vector2d>& points_world,
                             const std::vector<double>& spacings_m,
                             const std::vector<Eigen::Vector2d>& normals_world) {
  return Add(points_world, spacings_m, normals_world, true);
}

std::size_t PointMap::Restore(const std::vector<Eigen::Vector2d>& points_world,
                              const std::vector<double>& spacings_m,
                              const std::vector<Eigen::Vector2d>& normals_world) {
  return Add(points_world, spacings_m, normals_world, false);
}

std::size_t PointMap::Add(const std::vector<Eigen::Vector2d>& points_world,
                          const std::vector<double>& spacings_m,
                          const std::vector<Eigen::Vector2d>& normals_world, bool merge) {
  if (points_world.size() != spacings_m.size())
    throw std::invalid_argument("PointMap::Insert: one spacing per point is required");
  if (!normals_world.empty() && normals_world.size() != points_world.size())
    throw std::invalid_argument("PointMap::Insert: no normals, or one normal per point");
  Storage& s = *storage_;
  const std::size_t first_new = s.points.size();
  for (std::size_t i = 0; i < points_world.size(); ++i) {
    const Eigen::Vector2d& p = points_world[i];
    if (!p.allFinite()) continue;
    // After de-duplication the gap between kept points is at least one cell.
    const double spacing = std::clamp(std::max(spacings_m[i], options_.cell_size_m), 0.0,
                                      options_.max_point_spacing_m);
    // The sample joins the point whose first sample is nearest, if within one cell diagonal
    // (looked up in the 3×3 cells around): a noisy wall then stays one layer of points thick.
    bool inserted_new = true;
    std::uint32_t existing = 0;
    if (options_.cell_size_m > 0.0 && !merge) {
      s.occupied_cells.Emplace(CellIndex(p.x(), options_.cell_size_m),
                               CellIndex(p.y(), options_.cell_size_m),
                               static_cast<std::uint32_t>(s.points.size()));
    } else if (options_.cell_size_m > 0.0) {
      existing = NearestHeld(s.occupied_cells, s.indexed, p, options_.cell_size_m);
      inserted_new = existing == CellTiles::kNone;
      if (inserted_new)
        s.occupied_cells.Emplace(CellIndex(p.x(), options_.cell_size_m),
                                 CellIndex(p.y(), options_.cell_size_m),
                                 static_cast<std::uint32_t>(s.points.size()));
    }
    Eigen::Vector2f normal = Eigen::Vector2f::Zero();
    if (!normals_world.empty() && normals_world[i].allFinite() && normals_world[i].norm() > 0.5)
      normal = normals_world[i].normalized().cast<float>();
    if (options_.cell_size_m > 0.0 && !inserted_new) {
      const std::uint32_t j = existing;
      s.spacings[j] = std::min(s.spacings[j], spacing);
      if (s.samples[j] < kMaxMergedSamples) ++s.samples[j];
      const double weight = 1.0 / s.samples[j];
      s.points[j] += weight * (p - s.points[j]);
      if (normal.squaredNorm() > 0.0) {
        Eigen::Vector2f& n = s.normals[j];
        if (n.squaredNorm() == 0.0f) {
          n = normal;
        } else {
          const Eigen::Vector2f aligned = n.dot(normal) < 0.0f ? -normal : normal;
          const Eigen::Vector2f mean = n + static_cast<float>(weight) * (aligned - n);
          if (mean.squaredNorm() > 1e-6f) n = mean.normalized();
        }
      }
      continue;
    }
    const std::int64_t search_key = CellKey(p, kSearchCellM);
    std::uint32_t list = s.search_cell_of.Find(search_key);
    if (list == CellTable::kNone) {
      list = static_cast<std::uint32_t>(s.search_cells.size());
      s.search_cell_of.Emplace(search_key, list);
      s.search_cells.emplace_back();
    }
    s.search_cells[list].push_back(static_cast<std::uint32_t>(s.points.size()));
    const std::int64_t block_x = BlockIndex(p.x()), block_y = BlockIndex(p.y());
    s.blocks.try_emplace(CellKey(block_x, block_y), Storage::Block{block_x, block_y, {}})
        .first->second.slots.push_back(static_cast<std::uint32_t>(s.points.size()));
    s.points.push_back(p);
    s.indexed.push_back(p);
    s.bounds.extend(p);
    s.spacings.push_back(spacing);
    s.normals.push_back(normal);
    s.samples.push_back(1);
    s.misses.push_back(0);
    s.alive.push_back(1);
  }
  if (s.points.size() > first_new)
    s.tree.addPoints(static_cast<std::uint32_t>(first_new),
                     static_cast<std::uint32_t>(s.points.size() - 1));
  return s.points.size() - first_new;
}

bool PointMap::Insert(const Eigen::Vector2d& point_world, double spacing_m) {
  return Insert(std::vector<Eigen::Vector2d>{point_world}, std::vector<double>{spacing_m}) == 1;
}

std::size_t PointMap::InsertScan(const LaserScan& scan, const Pose2D& T_world_laser) {
  std::vector<Eigen::Vector2d> points, normals;
  std::vector<double> spacings;
  const std::size_t n = scan.size();
  const Eigen::Rotation2Dd R_world_laser(T_world_laser.yaw_rad);
  // Each valid beam's end point in the laser frame, computed once (each is used thrice).
  std::vector<Eigen::Vector2d> laser_points(n);
  std::vector<std::uint8_t> valid(n, 0);
  const BearingCosines& bearings = BearingCosinesOf(scan.layout);
  for (std::size_t k = 0; k < n; ++k)
    if (scan.IsValid(k)) {
      valid[k] = 1;
      laser_points[k] = scan.ranges_m[k] * Eigen::Vector2d(bearings.cos[k], bearings.sin[k]);
    }
  const PoseTransform to_world(T_world_laser);
  for (std::size_t k = 0; k < n; ++k) {
    if (!valid[k]) continue;
    const Eigen::Vector2d p = laser_points[k];
    double spacing = std::numeric_limits<double>::infinity();
    std::optional<Eigen::Vector2d> before, after;
    if (k > 0 && valid[k - 1]) before = laser_points[k - 1];
    if (k + 1 < n && valid[k + 1]) after = laser_points[k + 1];
    if (before) spacing = (*before - p).norm();
    if (after) spacing = std::min(spacing, (*after - p).norm());
    if (!std::isfinite(spacing)) spacing = scan.ranges_m[k] * scan.layout.angle_increment_rad;
    // Neighbours farther than the spacing bound are across a depth jump, not on this surface.
    if (before && (*before - p).norm() > options_.max_point_spacing_m) before.reset();
    if (after && (*after - p).norm() > options_.max_point_spacing_m) after.reset();
    Eigen::Vector2d normal = Eigen::Vector2d::Zero();
    const Eigen::Vector2d tangent = (after ? *after : p) - (before ? *before : p);
    if (tangent.norm() > 1e-9) {
      normal = Eigen::Vector2d(-tangent.y(), tangent.x()).normalized();
      if (normal.dot(p) > 0.0) normal = -normal;  // facing the laser
      normal = R_world_laser * normal;
    }
    points.push_back(to_world(p));  // (3.6)
    spacings.push_back(spacing);
    normals.push_back(normal);
  }
  return Insert(points, spacings, normals);
}

std::size_t PointMap::CarveFreeSpace(const LaserScan& scan, const Pose2D& T_world_laser,
                                     double margin_m, double margin_per_m,
                                     std::uint32_t first_index) {
  scan.CheckConsistent();
  if (!(margin_m >= 0.0)) throw std::invalid_argument("CarveFreeSpace: margin_m must be >= 0");
  if (!(margin_per_m >= 0.0) || !(margin_per_m < 1.0))
    throw std::invalid_argument("CarveFreeSpace: margin_per_m must be in [0, 1)");
  const std::size_t n = scan.size();
  double reach_m = 0.0;
  for (std::size_t k = 0; k < n; ++k)
    if (scan.IsValid(k)) reach_m = std::max(reach_m, scan.ranges_m[k]);
  if (reach_m <= margin_m || empty() || first_index >= size()) return 0;
  // The nearest return among a beam and its two neighbours: a point is only seen through when
  // all three passed it, so that points beside a depth jump are not carved by discretisation.
  std::vector<double> nearest(n, -1.0);
  for (std::size_t k = 1; k + 1 < n; ++k)
    if (scan.IsValid(k - 1) && scan.IsValid(k) && scan.IsValid(k + 1))
      nearest[k] = std::min({scan.ranges_m[k - 1], scan.ranges_m[k], scan.ranges_m[k + 1]});
  const PoseTransform T_laser_world(T_world_laser.Inverse());
  const double angle_min = scan.layout.angle_min_rad;
  const double increment = scan.layout.angle_increment_rad;
  const CarvedBlocks carved{T_world_laser, scan.layout,  nearest,
                            margin_m,      margin_per_m, MaxIndexDisplacement()};
  Storage& s = *storage_;
  std::size_t removed = 0;
  std::vector<std::pair<std::uint32_t, double>> candidates;
  RadiusSearchInBlocks(
      T_world_laser.Translation(), reach_m,
      [&carved](std::int64_t ix, std::int64_t iy) { return carved.MayHoldCarved(ix, iy); },
      candidates, first_index);
  for (const auto& [index, unused] : candidates) {
    const Eigen::Vector2d q = T_laser_world(s.points[index]);
    const double range = q.norm();
    if (range <= scan.layout.range_min_m) continue;
    const double beam = NearestBeamPosition(q, angle_min, increment, n);
    if (!(beam >= 0.0) || beam > static_cast<double>(n - 1)) continue;
    const double hit = nearest[static_cast<std::size_t>(beam)];
    if (hit < 0.0 || range >= hit - margin_m - margin_per_m * hit) continue;
    if (s.misses[index] < std::numeric_limits<std::uint16_t>::max()) ++s.misses[index];
    if (s.misses[index] <= s.samples[index]) continue;
    s.alive[index] = 0;
    s.tree.removePoint(index);
    // Out of the lists that searches and simulated scans walk, which skipped it anyway.
    const Eigen::Vector2d& first_sample = s.indexed[index];
    // Every live point's search cell has a list (Add made it).
    EraseIndex(*s.SearchCell(CellKey(first_sample, kSearchCellM)), index);
    EraseIndex(
        s.blocks.at(CellKey(BlockIndex(first_sample.x()), BlockIndex(first_sample.y()))).slots,
        index);
    if (options_.cell_size_m > 0.0)
      s.occupied_cells.EraseIfHolds(CellIndex(first_sample.x(), options_.cell_size_m),
                                    CellIndex(first_sample.y(), options_.cell_size_m), index);
    ++removed;
  }
  s.removed += removed;
  return removed;
}

double PointMap::MaxIndexDisplacement() const {
  return options_.cell_size_m * std::sqrt(2.0);
}

std::vector<std::pair<std::uint32_t, double>> PointMap::RadiusSearch(const Eigen::Vector2d& centre,
                                                                     double radius_m) const {
  std::vector<std::pair<std::uint32_t, double>> found;
  RadiusSearch(centre, radius_m, found);
  return found;
}

void PointMap::RadiusSearch(const Eigen::Vector2d& centre, double radius_m,
                            std::vector<std::pair<std::uint32_t, double>>& found) const {
  found.clear();
  if (empty() || !(radius_m > 0.0)) return;
  const double widened = radius_m + MaxIndexDisplacement();
  const double radius2 = radius_m * radius_m;
  const Storage& s = *storage_;
  // Lists live point i if its mean lies within the radius.
  const auto offer = [&](std::uint32_t i) {
    if (!s.alive[i]) return;
    const double d2 = (s.points[i] - centre).squaredNorm();
    if (d2 < radius2) found.emplace_back(i, d2);
  };
  const Eigen::Vector2d farthest =
      (s.bounds.max() - centre).cwiseAbs().cwiseMax((s.bounds.min() - centre).cwiseAbs());
  if (farthest.squaredNorm() < widened * widened) {
    // The tree would return every point (long-range simulated scans of a building-sized map):
    // the same set, in index order, without the walk.
    found.reserve(live_size());
    for (std::size_t i = 0; i < s.points.size(); ++i) offer(static_cast<std::uint32_t>(i));
    return;
  }
  // Cells keyed by first samples, which lie within `widened` of the centre for every mean
  // within the radius: the cells over [centre ± widened] hold them all.
  const std::int64_t cell_x0 = CellIndex(centre.x() - widened, kSearchCellM);
  const std::int64_t cell_x1 = CellIndex(centre.x() + widened, kSearchCellM);
  const std::int64_t cell_y0 = CellIndex(centre.y() - widened, kSearchCellM);
  const std::int64_t cell_y1 = CellIndex(centre.y() + widened, kSearchCellM);
  if ((cell_x1 - cell_x0 + 1) * (cell_y1 - cell_y0 + 1) <= kMaxSearchCells) {
    for (std::int64_t ix = cell_x0; ix <= cell_x1; ++ix)
      for (std::int64_t iy = cell_y0; iy <= cell_y1; ++iy) {
        const std::uint32_t list = s.search_cell_of.Find(CellKey(ix, iy));
        if (list == CellTable::kNone) continue;
        for (const std::uint32_t i : s.search_cells[list]) {  // live points only
          const double d2 = (s.points[i] - centre).squaredNorm();
          if (d2 < radius2) found.emplace_back(i, d2);
        }
      }
    return;
  }
  nanoflann::RadiusResultSet<double, std::uint32_t> result(widened * widened, found);
  const double query[2] = {centre.x(), centre.y()};
  storage_->tree.findNeighbors(result, query, nanoflann::SearchParams(32, 0.0f, false));
  // Distances to the cell means, and only those within the radius.
  std::size_t kept = 0;
  for (const auto& [index, unused] : found) {
    const double d2 = (storage_->points[index] - centre).squaredNorm();
    if (d2 < radius2) found[kept++] = {index, d2};
  }
  found.resize(kept);
}

std::int64_t PointMap::BlockIndex(double coordinate_m) {
  return CellIndex(coordinate_m, kBlockSideM);
}

const std::vector<std::uint32_t>* PointMap::Block(std::int64_t ix, std::int64_t iy) const {
  const auto block = storage_->blocks.find(CellKey(ix, iy));
  return block == storage_->blocks.end() ? nullptr : &block->second.slots;
}

void PointMap::RadiusSearchInBlocks(
    const Eigen::Vector2d& centre, double radius_m,
    const std::function<bool(std::int64_t, std::int64_t)>& keep_block,
    std::vector<std::pair<std::uint32_t, double>>& found, std::uint32_t first_index) const {
  found.clear();
  if (empty() || !(radius_m > 0.0)) return;
  const Storage& s = *storage_;
  const double widened = radius_m + MaxIndexDisplacement();
  const BlockRange map = block_range();
  const BlockRange box{std::max(map.x0, BlockIndex(centre.x() - widened)),
                       std::min(map.x1, BlockIndex(centre.x() + widened)),
                       std::max(map.y0, BlockIndex(centre.y() - widened)),
                       std::min(map.y1, BlockIndex(centre.y() + widened))};
  if (box.x1 < box.x0 || box.y1 < box.y0) return;
  const double radius2 = radius_m * radius_m;
  const auto search = [&](const Storage::Block& block) {
    if (block.slots.empty() || block.slots.back() < first_index) return;
    if (!keep_block(block.ix, block.iy)) return;
    const auto from = first_index == 0
                          ? block.slots.begin()
                          : std::lower_bound(block.slots.begin(), block.slots.end(), first_index);
    for (auto slot = from; slot != block.slots.end(); ++slot) {
      const std::uint32_t i = *slot;
      if (!s.alive[i]) continue;
      const double d2 = (s.points[i] - centre).squaredNorm();
      if (d2 < radius2) found.emplace_back(i, d2);
    }
  };
  // The box's blocks one by one, or every block when the box has more (a huge radius).
  const double box_blocks = (static_cast<double>(box.x1) - static_cast<double>(box.x0) + 1.0) *
                            (static_cast<double>(box.y1) - static_cast<double>(box.y0) + 1.0);
  if (box_blocks > static_cast<double>(s.blocks.size())) {
    for (const auto& [key, block] : s.blocks)
      if (block.ix >= box.x0 && block.ix <= box.x1 && block.iy >= box.y0 && block.iy <= box.y1)
        search(block);
    return;
  }
  for (std::int64_t ix = box.x0; ix <= box.x1; ++ix)
    for (std::int64_t iy = box.y0; iy <= box.y1; ++iy) {
      const auto block = s.blocks.find(CellKey(ix, iy));
      if (block != s.blocks.end()) search(block->second);
    }
}

PointMap::BlockRange PointMap::block_range() const {
  const Eigen::AlignedBox2d& bounds = storage_->bounds;
  if (bounds.isEmpty()) return {};
  return {BlockIndex(bounds.min().x()), BlockIndex(bounds.max().x()), BlockIndex(bounds.min().y()),
          BlockIndex(bounds.max().y())};
}

std::vector<std::pair<std::uint32_t, double>> PointMap::KNearest(const Eigen::Vector2d& centre,
                                                                 std::size_t k) const {
  k = std::min(k, size());
  std::vector<std::uint32_t> indices(k);
  std::vector<double> distances(k);
  std::vector<std::pair<std::uint32_t, double>> found;
  if (k == 0) return found;
  nanoflann::KNNResultSet<double, std::uint32_t> result(k);
  result.init(indices.data(), distances.data());
  const double query[2] = {centre.x(), centre.y()};
  storage_->tree.findNeighbors(result, query, nanoflann::SearchParams());
  if (MaxIndexDisplacement() == 0.0) {
    for (std::size_t i = 0; i < result.size(); ++i) found.emplace_back(indices[i], distances[i]);
    return found;
  }
  // The tree ranks first samples; a cell mean is at most one displacement δ away from its first
  // sample, so every mean nearer than the k-th found one lies within d_k + 2δ of the first samples.
  double d_k = 0.0;
  for (std::size_t i = 0; i < result.size(); ++i) d_k = std::max(d_k, std::sqrt(distances[i]));
  found = RadiusSearch(centre, d_k + 2.0 * MaxIndexDisplacement());
  const std::size_t keep = std::min(k, found.size());
  std::partial_sort(found.begin(), found.begin() + keep, found.end(),
                    [](const auto& a, const auto& b) { return a.second < b.second; });
  found.resize(keep);
  return found;
}

PointMap PointMapFromLines(const LineMap& lines, double spacing_m, PointMapOptions options) {
  PointMap map(options);
  std::vector<Eigen::Vector2d> points, normals;
  for (const Segment& segment : lines.segments) {
    const Eigen::Vector2d d = segment.b - segment.a;
    const Eigen::Vector2d normal =
        d.norm() > 1e-12 ? Eigen::Vector2d(-d.y(), d.x()).normalized() : Eigen::Vector2d::Zero();
    for (const auto& p : SampleLineMap(LineMap{{segment}}, spacing_m)) {
      points.push_back(p);
      normals.push_back(normal);
    }
  }
  map.Insert(points, std::vector<double>(points.size(), spacing_m), normals);
  return map;
}

}  // namespace scanloc
