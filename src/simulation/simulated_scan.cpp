#include "scanloc/simulation/simulated_scan.hpp"

#include <algorithm>
#include <cmath>

#include "scanloc/geometry/approximate_bearing.hpp"
#include "scanloc/maps/line_map.hpp"
#include "scanloc/maps/point_map.hpp"

namespace scanloc {
namespace {

// Beyond this many blocks from the map's blocks (coordinates near the limits of a double), the
// block walk's integer ring arithmetic is not used: the simulation visits every point.
constexpr double kMaxWalkBlocks = 1e9;

SimulatedScan EmptySimulation(const ScanLayout& layout) {
  const std::size_t beam_count = layout.beam_count;
  SimulatedScan sim;
  sim.layout = layout;
  sim.ranges_m.assign(beam_count, SimulatedScan::kNoReturn);
  sim.hit_source.assign(beam_count, HitSource::kNone);
  sim.hit_index.assign(beam_count, -1);
  return sim;
}

void Offer(SimulatedScan& sim, std::size_t beam, double range_m, HitSource source,
           std::int32_t index) {
  if (!(range_m < sim.layout.range_max_m) || range_m <= sim.layout.range_min_m) return;
  if (sim.hit_source[beam] == HitSource::kNone || range_m < sim.ranges_m[beam]) {
    sim.ranges_m[beam] = range_m;
    sim.hit_source[beam] = source;
    sim.hit_index[beam] = index;
  }
}

// A map point's offer: of equal ranges the lowest index is kept, as a pass over every point in
// index order keeps it, so that the scan does not depend on the order points are offered in.
void OfferPointHit(SimulatedScan& sim, std::size_t beam, double range_m, std::int32_t index) {
  if (sim.hit_source[beam] != HitSource::kNone && range_m == sim.ranges_m[beam] &&
      index < sim.hit_index[beam] && sim.hit_source[beam] == HitSource::kPoint) {
    sim.hit_index[beam] = index;
    return;
  }
  Offer(sim, beam, range_m, HitSource::kPoint, index);
}

// Range along the unit ray origin + t·u to segment [a, b]; negative when there is no hit.
double RaySegmentRange(const Eigen::Vector2d& origin, const Eigen::Vector2d& u,
                       const Eigen::Vector2d& a, const Eigen::Vector2d& b) {
  const Eigen::Vector2d d = b - a;
  const Eigen::Vector2d w = a - origin;
  const double denom = u.x() * d.y() - u.y() * d.x();
  const double length = d.norm();
  if (std::abs(denom) <= 1e-12 * std::max(length, 1e-12)) {
    // Seen edge-on: the beam runs along the segment's line; it meets the nearer vertex.
    if (std::abs(w.x() * u.y() - w.y() * u.x()) > 1e-9) return -1.0;
    const double ta = w.dot(u), tb = (b - origin).dot(u);
    const double t = std::min(ta, tb) > 0.0 ? std::min(ta, tb) : -1.0;
    return t;
  }
  const double t = (w.x() * d.y() - w.y() * d.x()) / denom;
  const double s = (w.x() * u.y() - w.y() * u.x()) / denom;
  const double tolerance = 1e-9 / std::max(length, 1e-12);
  if (s < -tolerance || s > 1.0 + tolerance || t <= 0.0) return -1.0;
  return t;
}

// Each beam's direction in the world, (cos φ, sin φ) with φ = yaw + bearing: computed once per
// simulated scan rather than once per point and beam.
std::vector<Eigen::Vector2d> BeamDirections(const ScanLayout& layout, const Pose2D& T_world_laser) {
  std::vector<Eigen::Vector2d> directions(layout.beam_count);
  for (std::size_t k = 0; k < layout.beam_count; ++k) {
    const double phi = T_world_laser.yaw_rad + layout.Bearing(k);
    directions[k] = {std::cos(phi), std::sin(phi)};
  }
  return directions;
}

// True when a map point about `bearing_rad` (laser frame, within kApproximateAtan2Bound), whose
// footprint reaches half_width_rad either side and which offers no range below nearest_offer_m,
// cannot change the scan: every beam it may cover already holds a hit nearer than that. Most
// points a simulated scan visits are such (hidden behind nearer ones), and this needs no exact
// bearing.
bool HiddenPoint(const SimulatedScan& sim, double bearing_rad, double half_width_rad,
                 double nearest_offer_m) {
  const double half = half_width_rad + 10.0 * kApproximateAtan2Bound;
  if (half >= 0.5 * M_PI) return false;
  return !AnyBeamInInterval(sim.layout, bearing_rad - half, 2.0 * half, [&](std::size_t k) {
    return !sim.IsValid(k) || !(sim.ranges_m[k] < nearest_offer_m);
  });
}

// (3.7) Offers map point i to the beams it covers as seen from T_world_laser; `directions` are
// BeamDirections(sim.layout, T_world_laser). With `cull`, a point that cannot change the scan
// (HiddenPoint) is passed over first: the scan is the same.
void OfferPoint(SimulatedScan& sim, const PointMap& map, const Pose2D& T_world_laser,
                const std::vector<Eigen::Vector2d>& directions,
                const PointSimulationOptions& options, std::uint32_t i, bool cull = true) {
  const ScanLayout& layout = sim.layout;
  const Eigen::Vector2d delta = map.point(i) - T_world_laser.Translation();
  const double range = delta.norm();  // (3.7) r_m
  if (!(range < layout.range_max_m) || range <= layout.range_min_m) return;
  // Half a step reaches the nearest beam, which is the chapter's binning; a wider footprint lets
  // the point hide the beams its neighbourhood covers.
  const double inc = layout.angle_increment_rad;
  const double half_width = std::min(
      M_PI / 2.0, std::max(0.5 * inc, 0.5 * options.footprint_factor * map.spacing(i) / range));
  // A point with a known normal is a small piece of surface (a surfel) of half-length
  // footprint_factor·spacing/2: a beam meets it where it crosses that surface, not at the point's
  // own range (off by spacing·tan(incidence) with 1° beams on oblique walls), and a beam that
  // crosses the surface beyond the patch passes by. A point without a normal is a disc.
  const Eigen::Vector2d normal = map.normal(i);
  const bool surfel = normal.squaredNorm() > 0.0;
  const double patch_half_m = std::max(0.5 * options.footprint_factor * map.spacing(i), 1e-3);
  // A surfel's crossing t satisfies |t·u − delta| ≤ patch_half_m, so t ≥ range − patch_half_m
  // (less a micrometre for rounding).
  if (cull && HiddenPoint(sim, ApproximateAtan2(delta.y(), delta.x()) - T_world_laser.yaw_rad,
                          half_width, surfel ? range - patch_half_m - 1e-6 : range))
    return;
  const double bearing = std::atan2(delta.y(), delta.x()) - T_world_laser.yaw_rad;  // (3.7) b_m
  ForEachBeamInInterval(layout, bearing - half_width, 2.0 * half_width, [&](std::size_t beam) {
    double beam_range = range;
    if (surfel) {
      const Eigen::Vector2d& u = directions[beam];
      const double cos_incidence = normal.dot(u);
      if (std::abs(cos_incidence) > 0.1) {
        const double t = normal.dot(delta) / cos_incidence;
        if (!(t > 0.0) || (t * u - delta).norm() > patch_half_m) return;
        beam_range = t;
      }
    }
    OfferPointHit(sim, beam, beam_range, static_cast<std::int32_t>(i));
  });
}

// How far a map point may reach towards the laser: a surfel's patch or a disc's footprint, never
// more than this in front of the point's own range (OfferPoint's patch_half_m, over all points).
double PatchMargin(const PointMap& map, const PointSimulationOptions& options) {
  return std::max(0.5 * options.footprint_factor * map.options().max_point_spacing_m, 1e-3);
}

// What the walk over the point map's blocks needs to know of one simulated scan.
struct BlockWalk {
  const PointMap& map;
  const Pose2D& T_world_laser;
  const std::vector<Eigen::Vector2d>& directions;
  const PointSimulationOptions& options;
  double patch_margin_m;
  std::size_t open_probe = 0;  // the beam last found open: it usually stays so (no return)
};

// True when some beam in [bearing − half, bearing + half] (laser frame) could still take a hit
// offered beyond limit_m: it has none yet, or its hit is not nearer than limit_m.
bool AnyBeamOpen(const SimulatedScan& sim, double bearing_rad, double half_rad, double limit_m) {
  if (half_rad >= 0.5 * M_PI) return true;
  return AnyBeamInInterval(sim.layout, bearing_rad - half_rad, 2.0 * half_rad, [&](std::size_t k) {
    return !sim.IsValid(k) || !(sim.ranges_m[k] < limit_m);
  });
}

// Whether the points of block (ix, iy) may change the scan. They lie in the block's square
// widened by the margin, within a disc around its centre; each is farther than the square's
// `nearest` point, so it offers no range below nearest − patch margin, and only to beams within
// its footprint (at most max(½ step, patch margin / nearest)) of a bearing inside the disc's
// angular span. When no beam there is open at that range, none of them
// can change the scan.
bool BlockMayShow(const SimulatedScan& sim, const BlockWalk& walk, std::int64_t ix,
                  std::int64_t iy) {
  const double side = PointMap::kBlockSideM;
  const Eigen::Vector2d centre((static_cast<double>(ix) + 0.5) * side,
                               (static_cast<double>(iy) + 0.5) * side);
  const double margin = walk.map.block_margin_m();
  const double radius = side * M_SQRT1_2 + margin;
  const Eigen::Vector2d delta = centre - walk.T_world_laser.Translation();
  const double centre_distance = delta.norm();
  // The distance to the square widened by the margin: nearer than any of its points.
  const Eigen::Vector2d gap = (delta.cwiseAbs().array() - (0.5 * side + margin)).max(0.0);
  const double nearest = gap.norm() - 1e-9;
  if (nearest >= sim.layout.range_max_m) return false;
  // Beside the laser any beam may see it.
  if (nearest <= walk.patch_margin_m || centre_distance <= radius) return true;
  const double half = std::asin(radius / centre_distance) +
                      std::max(0.5 * sim.layout.angle_increment_rad, walk.patch_margin_m / nearest);
  const double bearing = std::atan2(delta.y(), delta.x()) - walk.T_world_laser.yaw_rad;
  return AnyBeamOpen(sim, bearing, half, nearest - walk.patch_margin_m);
}

// True when every beam holds a hit nearer than limit_m: nothing offered beyond it can change them.
bool AllBeamsClosed(const SimulatedScan& sim, double limit_m, std::size_t& open_probe) {
  const auto open = [&](std::size_t k) { return !sim.IsValid(k) || !(sim.ranges_m[k] < limit_m); };
  if (open_probe < sim.size() && open(open_probe)) return false;
  for (std::size_t k = 0; k < sim.size(); ++k)
    if (open(k)) {
      open_probe = k;
      return false;
    }
  return true;
}

// Calls visit(ix, iy) for the blocks of ring r (Chebyshev distance r from block (ox, oy)) that lie
// in `range`.
template <class Visit>
void ForEachBlockInRing(std::int64_t ox, std::int64_t oy, std::int64_t r,
                        const PointMap::BlockRange& range, Visit visit) {
  const auto in = [](std::int64_t v, std::int64_t lo, std::int64_t hi) {
    return lo <= v && v <= hi;
  };
  if (r == 0) {
    if (in(ox, range.x0, range.x1) && in(oy, range.y0, range.y1)) visit(ox, oy);
    return;
  }
  const std::int64_t x_lo = std::max(ox - r, range.x0), x_hi = std::min(ox + r, range.x1);
  for (const std::int64_t iy : {oy - r, oy + r})
    if (in(iy, range.y0, range.y1))
      for (std::int64_t ix = x_lo; ix <= x_hi; ++ix) visit(ix, iy);
  const std::int64_t y_lo = std::max(oy - r + 1, range.y0), y_hi = std::min(oy + r - 1, range.y1);
  for (const std::int64_t ix : {ox - r, ox + r})
    if (in(ix, range.x0, range.x1))
      for (std::int64_t iy = y_lo; iy <= y_hi; ++iy) visit(ix, iy);
}

// Offers the points of the blocks around the laser ring by ring, nearest ring first, skipping the
// blocks whose beams are all closed nearer; stops once every beam is closed nearer than the next
// ring, or the next ring is out of range or beyond the map.
void WalkBlocks(SimulatedScan& sim, BlockWalk& walk) {
  const PointMap::BlockRange range = walk.map.block_range();
  const Eigen::Vector2d origin = walk.T_world_laser.Translation();
  const std::int64_t ox = PointMap::BlockIndex(origin.x()), oy = PointMap::BlockIndex(origin.y());
  const double first_ring = std::max({0.0, static_cast<double>(range.x0) - static_cast<double>(ox),
                                      static_cast<double>(ox) - static_cast<double>(range.x1),
                                      static_cast<double>(range.y0) - static_cast<double>(oy),
                                      static_cast<double>(oy) - static_cast<double>(range.y1)});
  const double last_ring = std::max({static_cast<double>(range.x1) - static_cast<double>(ox),
                                     static_cast<double>(ox) - static_cast<double>(range.x0),
                                     static_cast<double>(range.y1) - static_cast<double>(oy),
                                     static_cast<double>(oy) - static_cast<double>(range.y0)});
  const double side = PointMap::kBlockSideM, margin = walk.map.block_margin_m();
  for (double ring = first_ring; ring <= last_ring; ring += 1.0) {
    // Every block of ring r lies at least (r − 1)·side from the laser (its own block is ring 0).
    const double ring_nearest = std::max(0.0, (ring - 1.0) * side - margin) - 1e-9;
    if (ring_nearest >= sim.layout.range_max_m) return;
    if (AllBeamsClosed(sim, ring_nearest - walk.patch_margin_m, walk.open_probe)) return;
    ForEachBlockInRing(
        ox, oy, static_cast<std::int64_t>(ring), range, [&](std::int64_t ix, std::int64_t iy) {
          const std::vector<std::uint32_t>* points = walk.map.Block(ix, iy);
          if (points == nullptr || !BlockMayShow(sim, walk, ix, iy)) return;
          for (const std::uint32_t i : *points)
            if (walk.map.alive(i))
              OfferPoint(sim, walk.map, walk.T_world_laser, walk.directions, walk.options, i);
        });
  }
}

// Whether the ring arithmetic of WalkBlocks stays well inside 64-bit integers.
bool WalkableBlocks(const PointMap& map, const Pose2D& T_world_laser) {
  const PointMap::BlockRange range = map.block_range();
  const double limit = kMaxWalkBlocks * PointMap::kBlockSideM;
  const auto within = [&](double v) { return std::abs(v) < limit; };
  return range.x0 <= range.x1 && within(T_world_laser.x_m) && within(T_world_laser.y_m) &&
         within(static_cast<double>(range.x0) * PointMap::kBlockSideM) &&
         within(static_cast<double>(range.x1) * PointMap::kBlockSideM) &&
         within(static_cast<double>(range.y0) * PointMap::kBlockSideM) &&
         within(static_cast<double>(range.y1) * PointMap::kBlockSideM);
}

}  // namespace

bool MapView::empty() const {
  return (lines == nullptr || lines->empty()) && (points == nullptr || points->empty());
}

SimulatedScan SimulateFromLines(const LineMap& map, const ScanLayout& layout,
                                const Pose2D& T_world_laser) {
  SimulatedScan sim = EmptySimulation(layout);
  const Eigen::Vector2d origin = T_world_laser.Translation();
  for (std::size_t j = 0; j < map.segments.size(); ++j) {
    const Segment& segment = map.segments[j];
    const Eigen::Vector2d d1 = segment.a - origin, d2 = segment.b - origin;
    if (d1.norm() < 1e-12 || d2.norm() < 1e-12) continue;  // the laser sits on a vertex
    // (3.1) bearings of the two vertices, in the laser frame.
    const double b1 = std::atan2(d1.y(), d1.x()) - T_world_laser.yaw_rad;
    const double b2 = std::atan2(d2.y(), d2.x()) - T_world_laser.yaw_rad;
    // The triangle of visibility spans the shorter arc between them (a segment not through the
    // laser subtends less than π); its start may lie on either side of the ±π seam.
    const double sweep = NormalizeAngle(b2 - b1);
    const double from = sweep >= 0.0 ? b1 : b2;
    ForEachBeamInInterval(layout, from, std::abs(sweep), [&](std::size_t beam) {
      const double bearing = T_world_laser.yaw_rad + layout.Bearing(beam);
      const Eigen::Vector2d u(std::cos(bearing), std::sin(bearing));
      // Equivalent to the sine law (3.5), r(δ) = r1·sin α / sin(α + δ), evaluated per beam
      // without accumulating δ.
      const double range = RaySegmentRange(origin, u, segment.a, segment.b);
      if (range > 0.0) Offer(sim, beam, range, HitSource::kSegment, static_cast<std::int32_t>(j));
    });
  }
  return sim;
}

SimulatedScan SimulateFromPoints(const PointMap& map, const ScanLayout& layout,
                                 const Pose2D& T_world_laser,
                                 const PointSimulationOptions& options) {
  if (map.empty()) return EmptySimulation(layout);
  if (!WalkableBlocks(map, T_world_laser))
    return SimulateFromPointsBruteForce(map, layout, T_world_laser, options);
  // Front to back over the map's blocks: in a closed room only the blocks around the laser are
  // visited; beyond a doorway, only the blocks the open beams could see. The scan equals the
  // brute force's to the last tie (OfferPointHit).
  SimulatedScan sim = EmptySimulation(layout);
  const std::vector<Eigen::Vector2d> directions = BeamDirections(layout, T_world_laser);
  BlockWalk walk{map, T_world_laser, directions, options, PatchMargin(map, options)};
  WalkBlocks(sim, walk);
  return sim;
}

SimulatedScan SimulateFromPointsBruteForce(const PointMap& map, const ScanLayout& layout,
                                           const Pose2D& T_world_laser,
                                           const PointSimulationOptions& options) {
  SimulatedScan sim = EmptySimulation(layout);
  const std::vector<Eigen::Vector2d> directions = BeamDirections(layout, T_world_laser);
  for (std::size_t i = 0; i < map.size(); ++i)
    if (map.alive(i))
      OfferPoint(sim, map, T_world_laser, directions, options, static_cast<std::uint32_t>(i),
                 false);
  return sim;
}

SimulatedScan Simulate(const MapView& map, const ScanLayout& layout, const Pose2D& T_world_laser,
                       const PointSimulationOptions& options) {
  const bool has_lines = map.lines != nullptr && !map.lines->empty();
  const bool has_points = map.points != nullptr && !map.points->empty();
  if (has_lines && !has_points) return SimulateFromLines(*map.lines, layout, T_world_laser);
  if (has_points && !has_lines)
    return SimulateFromPoints(*map.points, layout, T_world_laser, options);
  if (!has_lines) return EmptySimulation(layout);
  SimulatedScan sim = SimulateFromLines(*map.lines, layout, T_world_laser);
  const SimulatedScan from_points = SimulateFromPoints(*map.points, layout, T_world_laser, options);
  for (std::size_t k = 0; k < sim.size(); ++k)
    if (from_points.IsValid(k))
      Offer(sim, k, from_points.ranges_m[k], HitSource::kPoint, from_points.hit_index[k]);
  return sim;
}

}  // namespace scanloc
