#include "scanloc/refinement/icp_refiner.hpp"

// The only source that sees PCL's headers: they are slow to compile.
// GCC 12 reports -Warray-bounds inside Eigen's SSE loads in the estimators PCL's ICP instantiates
// (SVD, point-to-plane LLS): a known false positive in library code.
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Warray-bounds"
#include <pcl/point_cloud.h>
#include <pcl/point_types.h>
#include <pcl/registration/icp.h>
#include <pcl/registration/transformation_estimation.h>
#include <pcl/registration/transformation_estimation_2D.h>
#include <pcl/search/kdtree.h>
#pragma GCC diagnostic pop

#include <Eigen/Dense>
#include <chrono>
#include <cmath>
#include <stdexcept>
#include <string>
#include <vector>

#include "scanloc/maps/line_map.hpp"
#include "scanloc/maps/point_map.hpp"

namespace scanloc {
namespace {

constexpr double kLineSampleSpacingM = 0.02;  // a line map becomes ICP's target sampled this finely
constexpr int kNormalNeighbours = 10;         // map points in the PCA that estimates a normal
constexpr std::size_t kMinPoints = 3;         // PCL's minimum number of correspondences

void Require(bool condition, const std::string& message) {
  if (!condition) throw std::invalid_argument("IcpOptions: " + message);
}

// The valid beams' end points in the laser frame.
std::vector<Eigen::Vector2d> ScanPoints(const LaserScan& scan) {
  std::vector<Eigen::Vector2d> points;
  points.reserve(scan.size());
  for (std::size_t i = 0; i < scan.size(); ++i)
    if (scan.IsValid(i)) points.push_back(scan.Point(i));
  return points;
}

// Map points within radius_m of the initial laser position, expressed in the initial laser frame:
// registering there keeps PCL's single-precision arithmetic near the origin even when the map's
// coordinates are large, and the identity is the initial guess.
std::vector<Eigen::Vector2d> MapPointsNear(const MapView& map, const Pose2D& T_world_laser,
                                           double radius_m) {
  const Eigen::Vector2d centre_world = T_world_laser.Translation();
  const Pose2D T_laser_world = T_world_laser.Inverse();
  std::vector<Eigen::Vector2d> points_laser;
  if (map.lines != nullptr && !map.lines->empty())
    for (const Eigen::Vector2d& p_world : SampleLineMap(*map.lines, kLineSampleSpacingM))
      if ((p_world - centre_world).norm() <= radius_m)
        points_laser.push_back(T_laser_world.Transform(p_world));
  if (map.points != nullptr && !map.points->empty())
    for (const auto& [index, squared_distance] : map.points->RadiusSearch(centre_world, radius_m))
      points_laser.push_back(T_laser_world.Transform(map.points->point(index)));
  return points_laser;
}

template <typename PointT>
typename pcl::PointCloud<PointT>::Ptr ToCloud(const std::vector<Eigen::Vector2d>& points) {
  typename pcl::PointCloud<PointT>::Ptr cloud(new pcl::PointCloud<PointT>);
  cloud->reserve(points.size());
  for (const Eigen::Vector2d& p : points) {
    PointT point;
    point.x = static_cast<float>(p.x());
    point.y = static_cast<float>(p.y());
    point.z = 0.0f;
    cloud->push_back(point);
  }
  return cloud;
}

// The 2D normal of every map point: the direction of least spread of its k nearest neighbours.
// Points whose neighbourhood does not define a direction (all coincident) are dropped.
pcl::PointCloud<pcl::PointNormal>::Ptr WithNormals2D(const std::vector<Eigen::Vector2d>& points) {
  const auto cloud = ToCloud<pcl::PointNormal>(points);
  pcl::search::KdTree<pcl::PointNormal> tree;
  tree.setInputCloud(cloud);
  pcl::PointCloud<pcl::PointNormal>::Ptr with_normals(new pcl::PointCloud<pcl::PointNormal>);
  pcl::Indices neighbours;
  std::vector<float> squared_distances;
  for (std::size_t i = 0; i < cloud->size(); ++i) {
    const int k = std::min<int>(kNormalNeighbours, static_cast<int>(cloud->size()));
    if (tree.nearestKSearch(static_cast<int>(i), k, neighbours, squared_distances) < 2) continue;
    Eigen::Vector2d mean = Eigen::Vector2d::Zero();
    for (const auto j : neighbours) mean += points[j];
    mean /= static_cast<double>(neighbours.size());
    Eigen::Matrix2d covariance = Eigen::Matrix2d::Zero();
    for (const auto j : neighbours)
      covariance += (points[j] - mean) * (points[j] - mean).transpose();
    if (!(covariance.trace() > 0.0)) continue;
    const Eigen::SelfAdjointEigenSolver<Eigen::Matrix2d> solver(covariance);
    const Eigen::Vector2d normal = solver.eigenvectors().col(0);  // smallest eigenvalue first
    pcl::PointNormal point = (*cloud)[i];
    point.normal_x = static_cast<float>(normal.x());
    point.normal_y = static_cast<float>(normal.y());
    point.normal_z = 0.0f;
    with_normals->push_back(point);
  }
  return with_normals;
}

// A planar rigid transform as PCL's 4×4 matrix.
Eigen::Matrix4f PlanarTransform(double x_m, double y_m, double yaw_rad) {
  Eigen::Matrix4f T = Eigen::Matrix4f::Identity();
  T(0, 0) = static_cast<float>(std::cos(yaw_rad));
  T(0, 1) = static_cast<float>(-std::sin(yaw_rad));
  T(1, 0) = static_cast<float>(std::sin(yaw_rad));
  T(1, 1) = static_cast<float>(std::cos(yaw_rad));
  T(0, 3) = static_cast<float>(x_m);
  T(1, 3) = static_cast<float>(y_m);
  return T;
}

// Point-to-line in the plane: minimises Σ (n_q · (R(θ)p + t − q))² over (t_x, t_y, θ), linearised
// about the identity (R(θ)p ≈ p + θ·(−p_y, p_x)) and solved as 3×3 normal equations; ICP's
// iterations remove the linearisation error. PCL's TransformationEstimationPointToPlaneLLS solves
// the 6-DoF problem, whose 6×6 system is singular for points and normals all in the plane z = 0.
class PointToLineEstimation2D
    : public pcl::registration::TransformationEstimation<pcl::PointNormal, pcl::PointNormal> {
 public:
  using Cloud = pcl::PointCloud<pcl::PointNormal>;

  void estimateRigidTransformation(const Cloud& source, const Cloud& target,
                                   Matrix4& T) const override {
    pcl::Correspondences pairs;
    for (std::size_t i = 0; i < source.size() && i < target.size(); ++i)
      pairs.emplace_back(static_cast<int>(i), static_cast<int>(i), 0.0f);
    estimateRigidTransformation(source, target, pairs, T);
  }
  void estimateRigidTransformation(const Cloud& source, const pcl::Indices& source_indices,
                                   const Cloud& target, Matrix4& T) const override {
    pcl::Correspondences pairs;
    for (const auto i : source_indices) pairs.emplace_back(i, i, 0.0f);
    estimateRigidTransformation(source, target, pairs, T);
  }
  void estimateRigidTransformation(const Cloud& source, const pcl::Indices& source_indices,
                                   const Cloud& target, const pcl::Indices& target_indices,
                                   Matrix4& T) const override {
    pcl::Correspondences pairs;
    for (std::size_t k = 0; k < source_indices.size() && k < target_indices.size(); ++k)
      pairs.emplace_back(source_indices[k], target_indices[k], 0.0f);
    estimateRigidTransformation(source, target, pairs, T);
  }
  void estimateRigidTransformation(const Cloud& source, const Cloud& target,
                                   const pcl::Correspondences& pairs, Matrix4& T) const override {
    Eigen::Matrix3d normal_matrix = Eigen::Matrix3d::Zero();
    Eigen::Vector3d rhs = Eigen::Vector3d::Zero();
    for (const pcl::Correspondence& pair : pairs) {
      const pcl::PointNormal& p = source[pair.index_query];
      const pcl::PointNormal& q = target[pair.index_match];
      const Eigen::Vector3d row(q.normal_x, q.normal_y, q.normal_y * p.x - q.normal_x * p.y);
      const double residual = q.normal_x * (p.x - q.x) + q.normal_y * (p.y - q.y);
      normal_matrix += row * row.transpose();
      rhs -= row * residual;
    }
    // Minimum-norm solution: a direction the pairs do not constrain (a corridor) is left alone.
    const Eigen::Vector3d step = normal_matrix.completeOrthogonalDecomposition().solve(rhs);
    T = step.allFinite() ? PlanarTransform(step.x(), step.y(), step.z()) : Matrix4::Identity();
  }
};

// Exposes the number of iterations PCL ran, which Registration keeps protected.
template <typename Icp>
class CountingIcp : public Icp {
 public:
  int iterations() const { return this->nr_iterations_; }
};

struct Alignment {
  Eigen::Matrix4f T_initial_final = Eigen::Matrix4f::Identity();  // in the initial laser frame
  bool converged = false;
  int iterations = 0;
};

template <typename Icp, typename CloudPtr>
Alignment Align(Icp& icp, const CloudPtr& source, const CloudPtr& target,
                const IcpOptions& options) {
  icp.setInputSource(source);
  icp.setInputTarget(target);
  icp.setMaxCorrespondenceDistance(options.max_correspondence_distance_m);
  icp.setMaximumIterations(options.max_iterations);
  icp.setTransformationEpsilon(options.transformation_epsilon);
  icp.setEuclideanFitnessEpsilon(options.euclidean_fitness_epsilon);
  // PCL counts running out of iterations as convergence; for a baseline that is a failure.
  icp.getConvergeCriteria()->setFailureAfterMaximumIterations(true);
  typename CloudPtr::element_type aligned;
  icp.align(aligned);
  return {icp.getFinalTransformation(), icp.hasConverged(), icp.iterations()};
}

Alignment Register(const std::vector<Eigen::Vector2d>& source_laser,
                   const std::vector<Eigen::Vector2d>& target_laser, const IcpOptions& options) {
  if (!options.point_to_plane) {
    CountingIcp<pcl::IterativeClosestPoint<pcl::PointXYZ, pcl::PointXYZ>> icp;
    icp.setTransformationEstimation(
        pcl::make_shared<
            pcl::registration::TransformationEstimation2D<pcl::PointXYZ, pcl::PointXYZ>>());
    return Align(icp, ToCloud<pcl::PointXYZ>(source_laser), ToCloud<pcl::PointXYZ>(target_laser),
                 options);
  }
  const auto target = WithNormals2D(target_laser);
  if (target->size() < kMinPoints) return {};
  CountingIcp<pcl::IterativeClosestPointWithNormals<pcl::PointNormal, pcl::PointNormal>> icp;
  icp.setTransformationEstimation(pcl::make_shared<PointToLineEstimation2D>());
  return Align(icp, ToCloud<pcl::PointNormal>(source_laser), target, options);
}

}  // namespace

void IcpOptions::Validate() const {
  Require(std::isfinite(max_correspondence_distance_m) && max_correspondence_distance_m > 0.0,
          "max_correspondence_distance_m must be positive and finite");
  Require(max_iterations >= 1, "max_iterations must be >= 1");
  Require(std::isfinite(transformation_epsilon) && transformation_epsilon >= 0.0,
          "transformation_epsilon must be finite and >= 0");
  Require(std::isfinite(euclidean_fitness_epsilon) && euclidean_fitness_epsilon >= 0.0,
          "euclidean_fitness_epsilon must be finite and >= 0");
}

RefinementResult RefineIcp(const MapView& map, const LaserScan& scan,
                           const Pose2D& T_world_laser_initial, const ScoringOptions& scoring,
                           const IcpOptions& options) {
  const auto start = std::chrono::steady_clock::now();
  options.Validate();
  scan.CheckConsistent();
  if (!std::isfinite(T_world_laser_initial.x_m) || !std::isfinite(T_world_laser_initial.y_m) ||
      !std::isfinite(T_world_laser_initial.yaw_rad))
    throw std::invalid_argument("RefineIcp: the initial posture must be finite");

  RefinementResult result;
  result.T_world_laser = T_world_laser_initial;
  const PostureScore before = ScorePosture(map, scan, T_world_laser_initial, scoring);
  result.test_before = result.test_after = before.test;
  result.distance_before = result.distance_after = before.distance;

  const std::vector<Eigen::Vector2d> source_laser = ScanPoints(scan);
  const std::vector<Eigen::Vector2d> target_laser =
      MapPointsNear(map, T_world_laser_initial, scan.layout.range_max_m);
  Alignment alignment;
  if (source_laser.size() >= kMinPoints && target_laser.size() >= kMinPoints)
    alignment = Register(source_laser, target_laser, options);
  result.iterations = alignment.iterations;

  const Eigen::Matrix4f& T = alignment.T_initial_final;
  const Pose2D T_initial_final(T(0, 3), T(1, 3), std::atan2(T(1, 0), T(0, 0)));
  if (alignment.iterations > 0 && std::isfinite(T_initial_final.x_m) &&
      std::isfinite(T_initial_final.y_m) && std::isfinite(T_initial_final.yaw_rad)) {
    result.T_world_laser = (T_world_laser_initial * T_initial_final).Normalized();
    result.converged = alignment.converged;
    const PostureScore after = ScorePosture(map, scan, result.T_world_laser, scoring);
    result.test_after = after.test;
    result.distance_after = after.distance;
  }
  result.time_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return result;
}

}  // namespace scanloc
