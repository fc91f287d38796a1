#include "scanloc/simulation/simulated_scan.hpp"

#include <algorithm>
#include <cmath>

#include "scanloc/common/parallel_for.hpp"
#include "scanloc/maps/line_map.hpp"
#include "scanloc/maps/point_map.hpp"

namespace scanloc {
namespace {

// The point-map scan searches this far first; in a closed room every beam finds its return there.
constexpr double kFirstRingM = 4.0;
// Fewer points than this per core are offered on one thread (a thread costs tens of µs).
constexpr std::size_t kMinPointsPerThread = 1500;

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

// Calls visit(beam) for each beam whose bearing (laser frame) lies in [from, from + span], span in
// [0, π]; bearings are compared modulo 2π so an interval across the ±π seam is handled.
template <class Visit>
void ForEachBeamInInterval(const ScanLayout& layout, std::size_t beam_count, double from_rad,
                           double span_rad, Visit visit) {
  const double inc = layout.angle_increment_rad;
  const double start = NormalizeAngle(from_rad);
  for (const double shift : {-2.0 * M_PI, 0.0, 2.0 * M_PI}) {
    const double lo = start + shift - layout.angle_min_rad;
    const double hi = lo + span_rad;
    const double first = std::max(0.0, std::ceil(lo / inc - 1e-9));
    const double last =
        std::min(static_cast<double>(beam_count) - 1.0, std::floor(hi / inc + 1e-9));
    for (double k = first; k <= last; k += 1.0) visit(static_cast<std::size_t>(k));
  }
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

// (3.7) Offers map point i to the beams it covers as seen from T_world_laser; `directions` are
// BeamDirections(sim.layout, T_world_laser).
void OfferPoint(SimulatedScan& sim, const PointMap& map, const Pose2D& T_world_laser,
                const std::vector<Eigen::Vector2d>& directions,
                const PointSimulationOptions& options, std::uint32_t i) {
  const ScanLayout& layout = sim.layout;
  const Eigen::Vector2d delta = map.point(i) - T_world_laser.Translation();
  const double range = delta.norm();  // (3.7) r_m
  if (!(range < layout.range_max_m) || range <= layout.range_min_m) return;
  const double bearing = std::atan2(delta.y(), delta.x()) - T_world_laser.yaw_rad;  // (3.7) b_m
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
  ForEachBeamInInterval(
      layout, sim.size(), bearing - half_width, 2.0 * half_width, [&](std::size_t beam) {
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
        Offer(sim, beam, beam_range, HitSource::kPoint, static_cast<std::int32_t>(i));
      });
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
    ForEachBeamInInterval(layout, layout.beam_count, from, std::abs(sweep), [&](std::size_t beam) {
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
  SimulatedScan sim = EmptySimulation(layout);
  // Nearest ring first: once every beam holds a hit nearer than anything beyond the ring could
  // offer (a point at distance d offers no range below d minus its patch), the farther points
  // cannot change the scan, which equals the brute force. In a closed room only the first ring is
  // searched; one beam without a return (a doorway, open space) needs the rest of the range, and
  // on the benchmark logs nearly every scan has one, so the rest is searched at once (rings
  // doubling up to the range searched the inner points again at every ring).
  const double patch_margin_m = 0.5 * options.footprint_factor * map.options().max_point_spacing_m;
  const double max_range_m = layout.range_max_m;
  const std::vector<Eigen::Vector2d> directions = BeamDirections(layout, T_world_laser);
  // Reused from call to call (a session simulates a few scans per iteration): no allocation.
  thread_local std::vector<std::pair<std::uint32_t, double>> found_buffer;
  // A reference, not the name: inside the worker threads `found_buffer` would be their own.
  std::vector<std::pair<std::uint32_t, double>>& found = found_buffer;
  // Offers the points found at or beyond min_distance_m, split over the cores: each chunk fills
  // its own scan, merged in chunk order, which keeps the serial loop's result to the last tie.
  auto offer_found = [&](double min_distance_m) {
    const double min2 = min_distance_m * min_distance_m;
    std::vector<SimulatedScan> partial(ParallelChunkCount(found.size(), kMinPointsPerThread));
    ParallelFor(found.size(), kMinPointsPerThread,
                [&](std::size_t chunk, std::size_t begin, std::size_t end) {
                  SimulatedScan& part = chunk == 0 ? sim : partial[chunk];
                  if (chunk > 0) part = EmptySimulation(layout);
                  for (std::size_t i = begin; i < end; ++i)
                    if (found[i].second >= min2)
                      OfferPoint(part, map, T_world_laser, directions, options, found[i].first);
                });
    for (std::size_t chunk = 1; chunk < partial.size(); ++chunk)
      for (std::size_t k = 0; k < sim.size(); ++k)
        if (partial[chunk].IsValid(k))
          Offer(sim, k, partial[chunk].ranges_m[k], partial[chunk].hit_source[k],
                partial[chunk].hit_index[k]);
  };
  const double ring_m = std::min(max_range_m, kFirstRingM);
  map.RadiusSearch(T_world_laser.Translation(), ring_m, found);
  offer_found(0.0);
  if (ring_m >= max_range_m) return sim;
  const double settled_m = ring_m - patch_margin_m;
  bool settled = true;
  for (std::size_t k = 0; k < sim.size() && settled; ++k)
    settled = sim.IsValid(k) && sim.ranges_m[k] <= settled_m;
  if (settled) return sim;
  map.RadiusSearch(T_world_laser.Translation(), max_range_m, found);
  offer_found(ring_m);
  return sim;
}

SimulatedScan SimulateFromPointsBruteForce(const PointMap& map, const ScanLayout& layout,
                                           const Pose2D& T_world_laser,
                                           const PointSimulationOptions& options) {
  SimulatedScan sim = EmptySimulation(layout);
  const std::vector<Eigen::Vector2d> directions = BeamDirections(layout, T_world_laser);
  for (std::size_t i = 0; i < map.size(); ++i)
    if (map.alive(i))
      OfferPoint(sim, map, T_world_laser, directions, options, static_cast<std::uint32_t>(i));
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
