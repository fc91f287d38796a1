#include "scanloc/session/wide_search.hpp"

#include <algorithm>
#include <array>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>

#include "scanloc/maps/line_map.hpp"
#include "scanloc/maps/point_map.hpp"

namespace scanloc {
namespace {

struct Node {
  int heading = 0;  // index into the rotated beam sets
  int ox = 0, oy = 0;
  int level = 0;
  float score = 0.0f;
};

// The scan's endpoints in the laser frame: valid beams, evenly subsampled to at most max_beams.
std::vector<Eigen::Vector2d> Endpoints(const LaserScan& scan, int max_beams, double& max_range_m) {
  std::vector<std::size_t> valid;
  for (std::size_t i = 0; i < scan.size(); ++i)
    if (scan.IsValid(i)) valid.push_back(i);
  const std::size_t stride = std::max<std::size_t>(
      1, (valid.size() + max_beams - 1) / static_cast<std::size_t>(max_beams));
  std::vector<Eigen::Vector2d> points;
  max_range_m = 0.0;
  for (std::size_t k = 0; k < valid.size(); k += stride) {
    const double r = scan.ranges_m[valid[k]], bearing = scan.layout.Bearing(valid[k]);
    points.emplace_back(r * std::cos(bearing), r * std::sin(bearing));
    max_range_m = std::max(max_range_m, r);
  }
  return points;
}

// The map points within `radius_m` of the centre: the point map's, and the line map sampled.
std::vector<Eigen::Vector2d> MapPoints(const MapView& map, const Eigen::Vector2d& centre,
                                       double radius_m, double spacing_m) {
  std::vector<Eigen::Vector2d> points;
  if (map.points != nullptr && !map.points->empty())
    for (const auto& [index, d2] : map.points->RadiusSearch(centre, radius_m))
      points.push_back(map.points->point(index));
  if (map.lines != nullptr)
    for (const Eigen::Vector2d& p : SampleLineMap(*map.lines, spacing_m))
      if ((p - centre).norm() <= radius_m) points.push_back(p);
  return points;
}

// Builds in `field` the field over the box of `points` (the cells a splat reaches), within
// centre ± reach, its
// corner a whole number of cells from centre − reach (so that a posture's cells do not depend on
// the map's extent), and widened below by a top-level block: a block starting left of or below
// the points then still holds the maximum of the cells it covers (the bound stays exact). Cells
// beyond hold 0, as LikelihoodField::At says outside the grid.
void FieldOver(const std::vector<Eigen::Vector2d>& points, const Eigen::Vector2d& centre,
               double reach, const LikelihoodFieldOptions& options, LikelihoodField& field) {
  const double res = options.resolution_m;
  const Eigen::Vector2d corner = centre - Eigen::Vector2d(reach, reach);
  const Eigen::Vector2d far = centre + Eigen::Vector2d(reach, reach);
  Eigen::Vector2d low = far, high = corner;
  for (const Eigen::Vector2d& p : points) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  }
  const double margin = 3.0 * options.sigma_m + 2.0 * res;
  const double pad = margin + res * ((1 << (options.levels - 1)) - 1);
  Eigen::Vector2d min_world = (low.array() - pad).max(corner.array()).matrix();
  min_world = corner + res * ((min_world - corner) / res).array().floor().matrix();
  const Eigen::Vector2d max_world = (high.array() + margin).min(far.array()).matrix();
  field.Rebuild(points, min_world, max_world.cwiseMax(min_world), options);
}

// The headings searched: offsets first…last times step_rad from the window's heading. The step
// moves the farthest endpoint by at most one cell (Hess et al. 2016); a window of ±π or more is
// the whole circle, each heading once.
struct Headings {
  double step_rad = 0.0;
  int first = 0, last = 0;
  bool full_circle = false;
  // Heading steps between indices a and b (around the circle when it is whole).
  int Apart(int a, int b) const {
    const int d = std::abs(a - b), count = last - first + 1;
    return full_circle ? std::min(d, count - d) : d;
  }
};
// Whether two nodes are not distinct: moves less than `cells` apart (a disc) and headings less
// than `headings` steps apart. The headings and each axis are compared first (integers): a pair
// an axis alone puts `cells` apart is never nearer, and most pairs are told apart without hypot.
struct Near {
  const Headings* search_headings = nullptr;
  double cells = 0.0, headings = 0.0;
  bool operator()(const Node& a, const Node& b) const {
    if (!(search_headings->Apart(a.heading, b.heading) < headings)) return false;
    const int dx = a.ox - b.ox, dy = a.oy - b.oy;
    if (!(std::max(std::abs(dx), std::abs(dy)) < cells)) return false;
    return std::hypot(dx, dy) < cells;
  }
};

Headings SearchHeadings(double half_yaw_rad, double resolution_m, double max_range_m,
                        const WideSearchOptions& options) {
  Headings h;
  h.step_rad = std::max(options.min_heading_step_rad,
                        std::acos(std::max(-1.0, 1.0 - resolution_m * resolution_m /
                                                           (2.0 * max_range_m * max_range_m))));
  if (half_yaw_rad + 0.5 * h.step_rad >= M_PI) {
    const int count = static_cast<int>(std::ceil(2.0 * M_PI / h.step_rad));
    h.step_rad = 2.0 * M_PI / count;
    h.first = -(count / 2);
    h.last = h.first + count - 1;
    h.full_circle = true;
    return h;
  }
  h.last = static_cast<int>(std::ceil(half_yaw_rad / h.step_rad));
  h.first = -h.last;
  return h;
}

// Exact branch and bound over translations, every heading at the top: keeps the best leaves that
// are distinct (no two `Near`), so that a second peak is not crowded out by the first one's slopes.
class BranchAndBound {
 public:
  BranchAndBound(const LikelihoodField& field,
                 const std::vector<std::vector<Eigen::Vector2i>>& cells, int half_cells,
                 std::size_t pool, Near near, bool skip_shadowed)
      : field_(field), half_(half_cells), pool_(pool), near_(near), skip_shadowed_(skip_shadowed) {
    // Every node's move lies within ±half cells (children never pass +half).
    for (const std::vector<Eigen::Vector2i>& heading : cells)
      cells_.push_back(field.Split(heading, half_cells));
  }

  // The distinct best leaves, best first, found depth first from the top-level nodes of every
  // heading, best first.
  std::vector<Node> Run(long long& nodes_scored) {
    const int top = field_.levels() - 1, step = 1 << top;
    std::vector<Node> roots;
    for (int h = 0; h < static_cast<int>(cells_.size()); ++h)
      for (int oy = -half_; oy <= half_; oy += step)
        for (int ox = -half_; ox <= half_; ox += step) roots.push_back(Scored({h, ox, oy, top}));
    SortBestFirst(roots);
    for (const Node& root : roots) Descend(root);
    nodes_scored = scored_;
    SortBestFirst(best_);
    return best_;
  }

 private:
  static void SortBestFirst(std::vector<Node>& nodes) {
    std::stable_sort(nodes.begin(), nodes.end(),
                     [](const Node& a, const Node& b) { return a.score > b.score; });
  }
  Node Scored(Node node) {
    return WithQuanta(node, field_.SumQuanta(node.level, cells_[node.heading], node.ox, node.oy));
  }
  // The node scored by the sum of its heading's cells, in quanta.
  Node WithQuanta(Node node, unsigned quanta) {
    const std::size_t cells = cells_[node.heading].size();
    const float sum = static_cast<float>(quanta) * LikelihoodField::kQuantum;
    node.score = cells == 0 ? 0.0f : sum / cells;
    ++scored_;
    return node;
  }
  // The node's children (at most four, those within the window), scored: all four in one pass
  // over the cells when all lie within it, as most do.
  std::size_t Children(const Node& node, std::array<Node, 4>& children) {
    const int step = 1 << (node.level - 1), level = node.level - 1;
    std::size_t count = 0;
    if (node.ox + step <= half_ && node.oy + step <= half_) {
      const std::array<unsigned, 4> quanta =
          field_.SumQuantaOfFour(level, cells_[node.heading], node.ox, node.oy, step);
      for (const int dy : {0, step})
        for (const int dx : {0, step}) {
          children[count] =
              WithQuanta({node.heading, node.ox + dx, node.oy + dy, level}, quanta[count]);
          ++count;
        }
      return count;
    }
    for (const int dy : {0, step})
      for (const int dx : {0, step})
        if (node.ox + dx <= half_ && node.oy + dy <= half_)
          children[count++] = Scored({node.heading, node.ox + dx, node.oy + dy, level});
    return count;
  }
  float Threshold() const {
    if (best_.size() < pool_) return -1.0f;
    float worst = best_.front().score;
    for (const Node& n : best_) worst = std::min(worst, n.score);
    return worst;
  }
  // A leaf near a better kept one is dropped; otherwise it replaces the kept ones near it (all
  // worse), or the worst when the pool is full.
  void Offer(const Node& leaf) {
    for (const Node& kept : best_)
      if (near_(leaf, kept) && kept.score >= leaf.score) return;
    best_.erase(std::remove_if(best_.begin(), best_.end(),
                               [&](const Node& kept) { return near_(leaf, kept); }),
                best_.end());
    if (best_.size() >= pool_)
      best_.erase(std::min_element(best_.begin(), best_.end(),
                                   [](const Node& a, const Node& b) { return a.score < b.score; }));
    best_.push_back(leaf);
  }

  // True when every leaf of the node's block lies near one kept leaf that scores at least the
  // node's bound: Offer would drop each of them and change nothing, so the block need not be
  // searched. The block is a rectangle of moves of one heading and `near` a disc of moves (with a
  // test of headings), so its four corners decide.
  bool Shadowed(const Node& node) const {
    const int last = (1 << node.level) - 1;
    const int x1 = std::min(node.ox + last, half_), y1 = std::min(node.oy + last, half_);
    for (const Node& kept : best_) {
      if (kept.score < node.score) continue;
      bool all = true;
      for (const int y : {node.oy, y1})
        for (const int x : {node.ox, x1}) all = all && near_({node.heading, x, y, 0}, kept);
      if (all) return true;
    }
    return false;
  }

  void Descend(const Node& node) {
    if (node.score <= Threshold()) return;
    if (node.level == 0) return Offer(node);
    if (skip_shadowed_ && Shadowed(node)) return;
    // At most four children, kept on the stack and put best first by a stable insertion (the
    // order a stable sort gives, without its buffer on the heap at every node).
    std::array<Node, 4> children;
    const std::size_t count = Children(node, children);
    for (std::size_t i = 1; i < count; ++i) {
      const Node child = children[i];
      std::size_t at = i;
      for (; at > 0 && children[at - 1].score < child.score; --at) children[at] = children[at - 1];
      children[at] = child;
    }
    for (std::size_t i = 0; i < count; ++i) Descend(children[i]);
  }

  const LikelihoodField& field_;
  std::vector<LikelihoodField::MovedCells> cells_;  // per heading: beam cells at offset 0
  int half_;
  std::size_t pool_;
  Near near_;
  bool skip_shadowed_;
  std::vector<Node> best_;  // distinct leaves, at most pool_
  long long scored_ = 0;
};

}  // namespace

std::optional<SearchWindow> WholeMapWindow(const MapView& map) {
  Eigen::Vector2d low(HUGE_VAL, HUGE_VAL), high(-HUGE_VAL, -HUGE_VAL);
  auto add = [&](const Eigen::Vector2d& p) {
    low = low.cwiseMin(p);
    high = high.cwiseMax(p);
  };
  if (map.points != nullptr)
    for (std::size_t i = 0; i < map.points->size(); ++i)
      if (map.points->alive(i)) add(map.points->point(i));
  if (map.lines != nullptr)
    for (const auto& segment : map.lines->segments) {
      add(segment.a);
      add(segment.b);
    }
  if (!(low.array() <= high.array()).all()) return std::nullopt;
  const Eigen::Vector2d centre = 0.5 * (low + high);
  return SearchWindow{Pose2D(centre.x(), centre.y(), 0.0), 0.5 * (high - low).maxCoeff(), M_PI};
}

void WideSearchOptions::Validate() const {
  field.Validate();
  auto require = [](bool ok, const char* what) {
    if (!ok) throw std::invalid_argument(std::string("WideSearchOptions: ") + what);
  };
  require(max_candidates >= 1 && max_candidates <= 1000, "max_candidates must be in [1, 1000]");
  require(std::isfinite(min_separation_m) && min_separation_m >= 0.0, "min_separation_m >= 0");
  require(std::isfinite(min_separation_rad) && min_separation_rad >= 0.0,
          "min_separation_rad >= 0");
  require(max_beams >= 1, "max_beams must be >= 1");
  require(std::isfinite(min_heading_step_rad) && min_heading_step_rad > 0.0 &&
              min_heading_step_rad < 1.0,
          "min_heading_step_rad must be in (0, 1)");
}

WideSearchResult WideSearch(const MapView& map, const LaserScan& scan, const SearchWindow& window,
                            const WideSearchOptions& options, LikelihoodField* storage) {
  options.Validate();
  if (!(window.half_width_m >= 0.0) || !(window.half_yaw_rad >= 0.0) ||
      !std::isfinite(window.half_width_m) || !std::isfinite(window.half_yaw_rad))
    throw std::invalid_argument("WideSearch: the window's half sizes must be finite and >= 0");
  const auto start = std::chrono::steady_clock::now();
  WideSearchResult result;
  double max_range_m = 0.0;
  const std::vector<Eigen::Vector2d> endpoints = Endpoints(scan, options.max_beams, max_range_m);
  const double res = options.field.resolution_m;
  const Eigen::Vector2d centre(window.centre.x_m, window.centre.y_m);
  const double reach = window.half_width_m + max_range_m + 3.0 * options.field.sigma_m;
  const std::vector<Eigen::Vector2d> points =
      endpoints.empty() || map.empty() ? std::vector<Eigen::Vector2d>{}
                                       : MapPoints(map, centre, reach * std::sqrt(2.0), 0.5 * res);
  if (points.empty()) return result;
  LikelihoodField own;
  LikelihoodField& field = storage != nullptr ? *storage : own;
  FieldOver(points, centre, reach, options.field, field);
  const Headings headings = SearchHeadings(window.half_yaw_rad, res, max_range_m, options);
  const double step_rad = headings.step_rad;
  std::vector<std::vector<Eigen::Vector2i>> cells;
  std::vector<double> yaws;
  for (int k = headings.first; k <= headings.last; ++k) {
    Pose2D pose = window.centre;
    pose.yaw_rad = NormalizeAngle(pose.yaw_rad + k * step_rad);
    std::vector<Eigen::Vector2i> heading_cells;
    const PoseTransform T_world_laser(pose);
    for (const Eigen::Vector2d& p : endpoints)
      heading_cells.push_back(field.Cell(T_world_laser(p)));
    cells.push_back(std::move(heading_cells));
    yaws.push_back(pose.yaw_rad);
  }
  result.headings = static_cast<int>(yaws.size());
  const int half_cells = static_cast<int>(std::ceil(window.half_width_m / res));
  const double separation_cells = options.min_separation_m / res;
  const double separation_headings = options.min_separation_rad / step_rad;
  const Near near{&headings, separation_cells, separation_headings};
  BranchAndBound search(field, cells, half_cells, static_cast<std::size_t>(options.max_candidates),
                        near, options.skip_shadowed_blocks);
  for (const Node& leaf : search.Run(result.nodes_scored))
    result.candidates.push_back({Pose2D{window.centre.x_m + leaf.ox * res,
                                        window.centre.y_m + leaf.oy * res, yaws[leaf.heading]},
                                 leaf.score});
  result.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace scanloc
