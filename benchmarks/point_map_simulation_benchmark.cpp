// The point-map simulated scan (3.7) by the block walk against every map point, on maps of
// 10k to 10M points at one local density, and the cost of growing a map scan by scan (3.6).
//
// The world is a grid of closed square rooms, walls every 5 m sampled every 0.05 m (about 8 points
// per m²); a map of N points is the N wall samples nearest the laser, which stands at the centre
// of a room in the middle of the map. The laser's 20 m range then always covers about 10k points,
// whatever N is.

#include <benchmark/benchmark.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdint>
#include <iostream>
#include <map>
#include <memory>
#include <numeric>
#include <stdexcept>
#include <vector>

#include "scanloc/maps/point_map.hpp"
#include "scanloc/simulation/simulated_scan.hpp"

namespace scanloc {
namespace {

constexpr double kRoomSideM = 5.0;
constexpr double kWallSampleM = 0.05;
constexpr int kSamplesPerRoomSide = 100;  // kRoomSideM / kWallSampleM
// The grid holds 2·100 − 1 samples per 25 m² room (walls shared, crossings counted once).
constexpr double kPointsPerSquareMetre = (2.0 * kSamplesPerRoomSide - 1.0) / 25.0;
constexpr std::size_t kBeamCount = 2400;
constexpr double kRangeMaxM = 20.0;

const Pose2D kLaserInMiddleRoom(0.5 * kRoomSideM, 0.5 * kRoomSideM, 0.3);

ScanLayout BenchmarkLayout() {
  return MakeLayout(kBeamCount, 2.0 * M_PI, kRangeMaxM);
}

// The `count` wall samples nearest the laser, in raster order (as a map would be stored after
// scanning the area row by row).
std::vector<Eigen::Vector2d> RoomGridPoints(std::size_t count) {
  const Eigen::Vector2d centre = kLaserInMiddleRoom.Translation();
  // A square comfortably holding the disk of `count` points.
  const double radius_m = 1.05 * std::sqrt(count / (M_PI * kPointsPerSquareMetre)) + kRoomSideM;
  const auto half_samples = static_cast<std::int64_t>(std::ceil(radius_m / kWallSampleM));
  const auto centre_i = static_cast<std::int64_t>(std::lround(centre.x() / kWallSampleM));
  const auto centre_j = static_cast<std::int64_t>(std::lround(centre.y() / kWallSampleM));
  const auto on_wall = [](std::int64_t sample) { return sample % kSamplesPerRoomSide == 0; };

  std::vector<Eigen::Vector2d> candidates;
  for (std::int64_t j = centre_j - half_samples; j <= centre_j + half_samples; ++j) {
    const bool horizontal_wall = on_wall(j);
    for (std::int64_t i = centre_i - half_samples; i <= centre_i + half_samples; ++i)
      if (horizontal_wall || on_wall(i))
        candidates.emplace_back(i * kWallSampleM, j * kWallSampleM);
  }
  if (candidates.size() < count) throw std::logic_error("RoomGridPoints: square too small");

  std::vector<std::uint32_t> order(candidates.size());
  std::iota(order.begin(), order.end(), 0u);
  const auto nearer = [&](std::uint32_t a, std::uint32_t b) {
    return (candidates[a] - centre).squaredNorm() < (candidates[b] - centre).squaredNorm();
  };
  std::nth_element(order.begin(), order.begin() + count, order.end(), nearer);
  order.resize(count);
  std::sort(order.begin(), order.end());
  std::vector<Eigen::Vector2d> points;
  points.reserve(count);
  for (const std::uint32_t index : order) points.push_back(candidates[index]);
  return points;
}

// Each map is built once per process: the 10M one takes a while.
const PointMap& RoomGridMap(std::size_t count) {
  static std::map<std::size_t, std::unique_ptr<PointMap>> cache;
  auto& map = cache[count];
  if (!map) {
    const auto start = std::chrono::steady_clock::now();
    PointMapOptions options;
    options.cell_size_m = 0.0;  // exact point counts; the samples are 5 cm apart anyway
    map = std::make_unique<PointMap>(options);
    const auto points = RoomGridPoints(count);
    map->Insert(points, std::vector<double>(points.size(), kWallSampleM));
    const std::chrono::duration<double> elapsed = std::chrono::steady_clock::now() - start;
    std::cerr << "built a room-grid point map of " << map->size() << " points in "
              << elapsed.count() << " s\n";
  }
  return *map;
}

void SetMapCounters(benchmark::State& state, const PointMap& map, const SimulatedScan& sim) {
  state.counters["map_points"] = static_cast<double>(map.size());
  state.counters["points_in_range"] =
      static_cast<double>(map.RadiusSearch(kLaserInMiddleRoom.Translation(), kRangeMaxM).size());
  state.counters["beams_hit"] = static_cast<double>(
      std::count_if(sim.hit_source.begin(), sim.hit_source.end(),
                    [](HitSource source) { return source != HitSource::kNone; }));
}

void BM_SimulateFromPoints(benchmark::State& state) {
  const PointMap& map = RoomGridMap(static_cast<std::size_t>(state.range(0)));
  const ScanLayout layout = BenchmarkLayout();
  SimulatedScan sim;
  for (auto _ : state) {
    sim = SimulateFromPoints(map, layout, kLaserInMiddleRoom);
    benchmark::DoNotOptimize(sim.ranges_m.data());
  }
  SetMapCounters(state, map, sim);
}

void BM_SimulateFromPointsBruteForce(benchmark::State& state) {
  const PointMap& map = RoomGridMap(static_cast<std::size_t>(state.range(0)));
  const ScanLayout layout = BenchmarkLayout();
  SimulatedScan sim;
  for (auto _ : state) {
    sim = SimulateFromPointsBruteForce(map, layout, kLaserInMiddleRoom);
    benchmark::DoNotOptimize(sim.ranges_m.data());
  }
  SetMapCounters(state, map, sim);
  // The index must not change the answer, only its cost.
  if (SimulateFromPoints(map, layout, kLaserInMiddleRoom).ranges_m != sim.ranges_m)
    state.SkipWithError("indexed and brute-force simulated scans differ");
}

// The index's share of BM_SimulateFromPoints: the 20 m radius search alone.
void BM_PointMapRadiusSearch(benchmark::State& state) {
  const PointMap& map = RoomGridMap(static_cast<std::size_t>(state.range(0)));
  std::size_t found = 0;
  for (auto _ : state) {
    const auto neighbours = map.RadiusSearch(kLaserInMiddleRoom.Translation(), kRangeMaxM);
    found = neighbours.size();
    benchmark::DoNotOptimize(neighbours.data());
  }
  state.counters["map_points"] = static_cast<double>(map.size());
  state.counters["points_in_range"] = static_cast<double>(found);
}

constexpr std::int64_t kMapSizes[] = {10'000, 100'000, 1'000'000, 10'000'000};

void MapSizes(benchmark::internal::Benchmark* benchmark) {
  for (const std::int64_t size : kMapSizes) benchmark->Arg(size);
  benchmark->ArgName("map_points")->Unit(benchmark::kMillisecond);
}

BENCHMARK(BM_SimulateFromPoints)->Apply(MapSizes);
BENCHMARK(BM_SimulateFromPointsBruteForce)->Apply(MapSizes);
BENCHMARK(BM_PointMapRadiusSearch)->Apply(MapSizes);

// A 2,400-beam scan from the centre of a 5 m square room: r(θ) = (side / 2) / max(|cos θ|, |sin
// θ|).
LaserScan RoomCentreScan() {
  LaserScan scan;
  scan.layout = BenchmarkLayout();
  for (std::size_t k = 0; k < kBeamCount; ++k) {
    const double bearing = scan.layout.Bearing(k);
    scan.ranges_m.push_back(0.5 * kRoomSideM /
                            std::max(std::abs(std::cos(bearing)), std::abs(std::sin(bearing))));
  }
  return scan;
}

// The laser visits the rooms of a 1,000-room-wide grid row by row, one scan per room, so that
// every scan extends the map (its walls shared with earlier rooms are merged by the grid).
Pose2D RoomVisit(std::size_t visit) {
  constexpr std::size_t kRoomsPerRow = 1000;
  return {(static_cast<double>(visit % kRoomsPerRow) + 0.5) * kRoomSideM,
          (static_cast<double>(visit / kRoomsPerRow) + 0.5) * kRoomSideM, 0.01 * (visit % 7)};
}

// (3.6) InsertScan into a map with the default 5 cm de-duplication that already holds about
// state.range(0) points and grows with every iteration.
void BM_PointMapInsertScan(benchmark::State& state) {
  const LaserScan scan = RoomCentreScan();
  PointMap map;
  std::size_t visit = 0;
  while (map.size() < static_cast<std::size_t>(state.range(0)))
    map.InsertScan(scan, RoomVisit(visit++));
  const std::size_t initial_size = map.size();
  std::size_t added = 0;
  for (auto _ : state) added += map.InsertScan(scan, RoomVisit(visit++));
  state.SetItemsProcessed(static_cast<std::int64_t>(state.iterations() * kBeamCount));
  state.counters["initial_map_points"] = static_cast<double>(initial_size);
  state.counters["final_map_points"] = static_cast<double>(map.size());
  state.counters["points_added_per_scan"] =
      static_cast<double>(added) / static_cast<double>(state.iterations());
}

BENCHMARK(BM_PointMapInsertScan)
    ->Arg(0)
    ->Arg(1'000'000)
    ->ArgName("initial_map_points")
    ->Unit(benchmark::kMicrosecond);

}  // namespace
}  // namespace scanloc

BENCHMARK_MAIN();
