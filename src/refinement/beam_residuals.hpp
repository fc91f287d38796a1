#pragma once
// The refinement's residuals: each beam's range residual against the local line of the surface
// it hits, all beams of a problem in one Ceres residual block under a per-beam robust kernel.
// Private to the library (src/, not include/): Ceres stays a private dependency of scanloc, and
// only the refinement layer and its tests see this header.

#include <ceres/cost_function.h>
#include <ceres/sized_cost_function.h>

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "scanloc/geometry/pose2d.hpp"
#include "scanloc/likelihood/likelihood_distance.hpp"

namespace scanloc {

// The local line of the surface a beam hits: n·q = offset, n a unit normal.
struct SurfaceLine {
  Eigen::Vector2d normal;
  double offset = 0.0;
};

// One beam's residual against its surface line, for the laser posture (x, y, θ):
//   φ = θ + bearing, u = (cos φ, sin φ), p = (x, y)
//   t = (offset − n·p) / (n·u)                the range along the beam to the line (sine law)
//   plain:   residual = r − t
//   cosine:  residual = (r − t)·(n·u) = n·(p + r·u) − offset, the measured point's signed
//            distance to the line, which stays finite at grazing incidence.
//   Jacobians (u' = (−sin φ, cos φ)):
//     cosine: ∂/∂(x, y) = n, ∂/∂θ = r·(n·u')
//     plain:  ∂/∂(x, y) = n / (n·u), ∂/∂θ = (offset − n·p)·(n·u') / (n·u)²
struct BeamTerm {
  double cos_bearing = 1.0;
  double sin_bearing = 0.0;
  double range_m = 0.0;
  SurfaceLine line;

  // u from the heading's cosine and sine (computed once for all beams) by the angle sum.
  // `jacobian` (3 values) may be null. False when a plain residual is undefined (the beam runs
  // along the line).
  bool Evaluate(const double* pose, double cos_heading, double sin_heading, bool cosine,
                double& residual, double* jacobian) const {
    const double c = cos_heading * cos_bearing - sin_heading * sin_bearing;
    const double s = sin_heading * cos_bearing + cos_heading * sin_bearing;
    const Eigen::Vector2d& n = line.normal;
    const double nu = n.x() * c + n.y() * s;
    const double nu_dot = -n.x() * s + n.y() * c;
    const double np = n.x() * pose[0] + n.y() * pose[1];
    if (cosine) {
      residual = np + range_m * nu - line.offset;
      if (jacobian != nullptr) {
        jacobian[0] = n.x();
        jacobian[1] = n.y();
        jacobian[2] = range_m * nu_dot;
      }
      return true;
    }
    if (std::abs(nu) < 1e-12) return false;
    const double along = line.offset - np;
    residual = range_m - along / nu;
    if (jacobian != nullptr) {
      jacobian[0] = n.x() / nu;
      jacobian[1] = n.y() / nu;
      jacobian[2] = along * nu_dot / (nu * nu);
    }
    return true;
  }
};

// A robust kernel on s = e²: ρ(s), ρ'(s), ρ''(s), by the very operations of Ceres' CauchyLoss,
// HuberLoss and TukeyLoss with parameter a (equal to the bit: tested), without their virtual call
// per beam and evaluation (about 1 % of a session's instructions; the logarithm itself stays).
// The default is no kernel, ρ(s) = s.
class BeamKernel {
 public:
  BeamKernel() = default;
  BeamKernel(RobustKernel kernel, double a) : kind_(Of(kernel)), a_(a), b_(a * a), c_(1 / b_) {}

  bool robust() const { return kind_ != Kind::kNone; }
  // ρ'(s) and ρ''(s), bit for bit Evaluate's (Cauchy's without its logarithm); rho[0] is left
  // to the caller.
  void Derivatives(double s, double rho[3]) const {
    if (kind_ != Kind::kCauchy) return Evaluate(s, rho);
    const double sum = 1.0 + s * c_;
    const double inv = 1.0 / sum;
    rho[1] = std::max(std::numeric_limits<double>::min(), inv);
    rho[2] = -c_ * (inv * inv);
  }
  void Evaluate(double s, double rho[3]) const {
    switch (kind_) {
      case Kind::kNone:
        break;
      case Kind::kCauchy: {  // b·ln(1 + s/b)
        const double sum = 1.0 + s * c_;
        const double inv = 1.0 / sum;
        rho[0] = b_ * std::log(sum);
        rho[1] = std::max(std::numeric_limits<double>::min(), inv);
        rho[2] = -c_ * (inv * inv);
        return;
      }
      case Kind::kHuber:  // s inside a², 2a√s − a² beyond
        if (s > b_) {
          const double r = std::sqrt(s);
          rho[0] = 2.0 * a_ * r - b_;
          rho[1] = std::max(std::numeric_limits<double>::min(), a_ / r);
          rho[2] = -rho[1] / (2.0 * s);
        } else {
          rho[0] = s;
          rho[1] = 1.0;
          rho[2] = 0.0;
        }
        return;
      case Kind::kTukey:  // a²/3·(1 − (1 − s/a²)³) inside a², a²/3 beyond
        if (s <= b_) {
          const double value = 1.0 - s / b_;
          const double value_sq = value * value;
          rho[0] = b_ / 3.0 * (1.0 - value_sq * value);
          rho[1] = value_sq;
          rho[2] = -2.0 / b_ * value;
        } else {
          rho[0] = b_ / 3.0;
          rho[1] = 0.0;
          rho[2] = 0.0;
        }
        return;
    }
    rho[0] = s;
    rho[1] = 1.0;
    rho[2] = 0.0;
  }

 private:
  enum class Kind { kNone, kCauchy, kHuber, kTukey };
  static Kind Of(RobustKernel kernel) {
    switch (kernel) {
      case RobustKernel::kCauchy:
        return Kind::kCauchy;
      case RobustKernel::kHuber:
        return Kind::kHuber;
      case RobustKernel::kTukey:
        return Kind::kTukey;
    }
    return Kind::kNone;
  }

  Kind kind_ = Kind::kNone;
  double a_ = 0.0, b_ = 0.0, c_ = 0.0;  // a, a², 1/a²
};

// All beams of a problem in one residual block, each under its own robust kernel, with the same
// cost, gradient and Gauss–Newton model as one block per beam with the kernel as Ceres' loss
// function (Ceres' bookkeeping per block costs more than the residuals themselves). Per beam,
// with s = e² and (ρ, ρ', ρ'') the kernel at s, Ceres' corrector (ceres/corrector.cc) scales
// the residual and its Jacobian row by √ρ' when ρ'' ≤ 0 (Cauchy, Huber and Tukey always), else
// by √ρ'/(1 − α) and √ρ'·(1 − α), α = 1 − √(1 + 2sρ''/ρ'). Without a kernel the residuals are
// the plain ones.
//
// Ceres sees the corrected beams (ẽ, J) through four residuals, whatever their number: with
// JᵀJ = V·Λ·Vᵀ, three residuals r' = Λ^-½·Vᵀ·Jᵀẽ with Jacobian J' = Λ^½·Vᵀ, so that
// J'ᵀJ' = JᵀJ and J'ᵀr' = Jᵀẽ, and a fourth, with a zero Jacobian row, carrying the rest of the
// cost: √(‖ẽ‖² − ‖r'‖² + Σ(ρ − ẽ²)), where Σ(ρ − ẽ²) ≥ 0 for a concave kernel (ρ ≥ sρ').
// The cost ½Σρ, the gradient, the Gauss–Newton matrix, its column norms (Ceres' Jacobi
// scaling) and the model cost of any step ‖J·δ + ẽ‖² are the same as the beams' own, so
// Levenberg–Marquardt takes the same steps (to rounding), while Ceres' work per evaluation
// (the dense Jacobian, its scaling, JᵀJ) no longer grows with the beams.
class BeamsResidual : public ceres::CostFunction {
 public:
  BeamsResidual(std::vector<BeamTerm> beams, bool cosine, BeamKernel kernel = {});

  // Without Jacobians (Levenberg–Marquardt's trial steps, which read only the cost) the cost
  // alone, ½Σρ = ½‖r‖² with r = (√Σρ, 0, 0, 0): no Jacobian rows, corrections or eigen-solve.
  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

  std::size_t beam_count() const { return beams_.size(); }

  // r' (3), the remainder (1).
  static constexpr int kResiduals = 4;
  // Eigen-directions of JᵀJ with less than this fraction of the largest eigenvalue carry no
  // information (rounding): their residual and Jacobian row are zero.
  static constexpr double kMinRelativeInformation = 1e-14;

 private:
  bool EvaluateCost(const double* pose, double cos_heading, double sin_heading,
                    double* residuals) const;
  bool CachedAt(const double* pose) const;

  // Each beam's ρ from the last cost-only evaluation and the posture it was at. Levenberg–
  // Marquardt evaluates an accepted step's Jacobians at the very posture whose cost it just
  // evaluated: the kernel's values (its logarithm) are then taken from here, bit for bit. One
  // problem is solved by one thread (the refiner's solves run with one), so this is not shared.
  mutable std::vector<double> cached_rho_;
  mutable double cached_at_[3] = {0.0, 0.0, 0.0};
  mutable bool cached_ = false;

  std::vector<BeamTerm> beams_;
  bool cosine_;
  BeamKernel kernel_;
};

// A prior on the laser posture: the difference p − mean in the mean's frame (along, across,
// heading), each component times its weight. Its cost ½Σ(wᵢdᵢ)² adds to the beams'; a zero weight
// leaves that component to the beams alone.
class PriorResidual : public ceres::SizedCostFunction<3, 3> {
 public:
  PriorResidual(const Pose2D& mean, const Eigen::Vector3d& weights);

  bool Evaluate(double const* const* parameters, double* residuals,
                double** jacobians) const override;

 private:
  Pose2D mean_;
  Eigen::Vector3d weights_;
};

}  // namespace scanloc
