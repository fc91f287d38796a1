#pragma once
// The local surface line of a point map around a query point (a beam's end point): the line
// through its k nearest map points within a radius, when they are close and collinear enough.
// Private to the library, like beam_residuals.hpp.

#include <Eigen/Core>
#include <cstdint>
#include <utility>
#include <vector>

#include "beam_residuals.hpp"

namespace scanloc {

class PointMap;

struct PointLineFitOptions {
  double radius_m = 0.3;
  int neighbours = 5;
  // The fit is refused when √(λmin/λmax) of the points' spread exceeds this (a corner, a blob).
  double max_thickness = 0.8;
};

// The eigen-decomposition of the symmetric 2 × 2 matrix [a b; b c] in closed form: its
// eigenvalues and the unit eigenvector of the smaller (either sign).
struct SpreadAxes {
  double smallest = 0.0, largest = 0.0;
  Eigen::Vector2d minor_axis = Eigen::Vector2d::UnitX();
};
SpreadAxes SymmetricEigen2(double a, double b, double c);

// The line through the k nearest map points within the radius of `query`. False when fewer
// than two are found, or their spread is too round.
bool FitPointLine(const PointMap& points, const Eigen::Vector2d& query,
                  const PointLineFitOptions& options, SurfaceLine& line);

// One beam's fits over the outer iterations of one refinement, bit for bit those of
// FitPointLine, for less work: between iterations the end point moves by the posture's step,
// usually millimetres.
//  - The map points within radius + kPoolMarginM of the first query are kept; a query within
//    the margin of it finds its neighbours among them, the same set with the same distances as a
//    search of the map (the triangle inequality), else a new pool is searched around it.
//  - When the k nearest are the same points in the same order as at the last fit, the last line
//    is returned: the fit is a function of that sequence.
// The map must not change while one is in use; Reset() before the next refinement.
class BeamLineFits {
 public:
  static constexpr double kPoolMarginM = 0.05;

  void Reset();
  bool Fit(const PointMap& points, const Eigen::Vector2d& query, const PointLineFitOptions& options,
           SurfaceLine& line);

 private:
  bool has_pool_ = false;
  Eigen::Vector2d pool_centre_ = Eigen::Vector2d::Zero();
  struct PoolPoint {
    std::uint32_t index;
    Eigen::Vector2d point;
    double squared_distance;  // from pool_centre_
  };
  std::vector<PoolPoint> pool_;  // nearest the centre first, with coordinates read in a row
  std::vector<std::pair<std::uint32_t, double>> nearest_;  // the current query's k nearest
  bool has_fit_ = false;
  std::vector<std::uint32_t> fitted_;  // the k nearest of the last fit, nearest first
  bool fitted_ok_ = false;
  SurfaceLine fitted_line_;
};

}  // namespace scanloc
