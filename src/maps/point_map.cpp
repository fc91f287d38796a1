#include "scanloc/maps/point_map.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <optional>
#include <unordered_map>

#include <Eigen/Geometry>

// nanoflann 1.4 trips -Wmaybe-uninitialized in its own header when optimised.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wmaybe-uninitialized"
#include <nanoflann.hpp>
#pragma GCC diagnostic pop

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

using KdTree = nanoflann::KDTreeSingleIndexDynamicAdaptor<
    nanoflann::L2_Simple_Adaptor<double, CloudAdaptor>, CloudAdaptor, 2, std::uint32_t>;

std::int64_t CellKey(const Eigen::Vector2d& p, double cell_size_m) {
  const auto ix = static_cast<std::int64_t>(std::floor(p.x() / cell_size_m));
  const auto iy = static_cast<std::int64_t>(std::floor(p.y() / cell_size_m));
  return (ix << 32) ^ (iy & 0xffffffffLL);
}

}  // namespace

struct PointMap::Storage {
  std::vector<Eigen::Vector2d> points;
  std::vector<double> spacings;
  std::vector<Eigen::Vector2f> normals;  // float: normals need no more, and maps can be large
  std::unordered_map<std::int64_t, std::uint32_t> occupied_cells;
  CloudAdaptor adaptor{&points};
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

std::size_t PointMap::size() const { return storage_->points.size(); }
const Eigen::Vector2d& PointMap::point(std::size_t i) const { return storage_->points[i]; }
double PointMap::spacing(std::size_t i) const { return storage_->spacings[i]; }
Eigen::Vector2d PointMap::normal(std::size_t i) const {
  return storage_->normals[i].cast<double>();
}

std::size_t PointMap::Insert(const std::vector<Eigen::Vector2d>& points_world,
                             const std::vector<double>& spacings_m,
                             const std::vector<Eigen::Vector2d>& normals_world) {
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
    if (options_.cell_size_m > 0.0) {
      const auto [it, inserted] =
          s.occupied_cells.emplace(CellKey(p, options_.cell_size_m), s.points.size());
      if (!inserted) {
        s.spacings[it->second] = std::min(s.spacings[it->second], spacing);
        continue;
      }
    }
    s.points.push_back(p);
    s.spacings.push_back(spacing);
    Eigen::Vector2f normal = Eigen::Vector2f::Zero();
    if (!normals_world.empty() && normals_world[i].allFinite() &&
        normals_world[i].norm() > 0.5)
      normal = normals_world[i].normalized().cast<float>();
    s.normals.push_back(normal);
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
  for (std::size_t k = 0; k < n; ++k) {
    if (!scan.IsValid(k)) continue;
    const Eigen::Vector2d p = scan.Point(k);
    double spacing = std::numeric_limits<double>::infinity();
    std::optional<Eigen::Vector2d> before, after;
    if (k > 0 && scan.IsValid(k - 1)) before = scan.Point(k - 1);
    if (k + 1 < n && scan.IsValid(k + 1)) after = scan.Point(k + 1);
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
    points.push_back(T_world_laser.Transform(p));  // (3.6)
    spacings.push_back(spacing);
    normals.push_back(normal);
  }
  return Insert(points, spacings, normals);
}

std::vector<std::pair<std::uint32_t, double>> PointMap::RadiusSearch(const Eigen::Vector2d& centre,
                                                                     double radius_m) const {
  std::vector<std::pair<std::uint32_t, double>> found;
  if (empty() || !(radius_m > 0.0)) return found;
  nanoflann::RadiusResultSet<double, std::uint32_t> result(radius_m * radius_m, found);
  const double query[2] = {centre.x(), centre.y()};
  storage_->tree.findNeighbors(result, query, nanoflann::SearchParams(32, 0.0f, false));
  return found;
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
  for (std::size_t i = 0; i < result.size(); ++i) found.emplace_back(indices[i], distances[i]);
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
