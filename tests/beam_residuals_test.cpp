#include "refinement/beam_residuals.hpp"

#include <ceres/ceres.h>
#include <gtest/gtest.h>

#include <Eigen/Dense>
#include <cmath>
#include <memory>
#include <ostream>
#include <random>
#include <string>
#include <vector>

namespace scanloc {
namespace {

// The reference: one Ceres residual block per beam, the kernel as Ceres' own loss function.
class OneBeam : public ceres::SizedCostFunction<1, 3> {
 public:
  OneBeam(const BeamTerm& beam, bool cosine) : beam_(beam), cosine_(cosine) {}
  bool Evaluate(double const* const* parameters, double* residual,
                double** jacobians) const override {
    const double* pose = parameters[0];
    return beam_.Evaluate(pose, std::cos(pose[2]), std::sin(pose[2]), cosine_, residual[0],
                          jacobians != nullptr ? jacobians[0] : nullptr);
  }

 private:
  BeamTerm beam_;
  bool cosine_;
};

enum class Kernel { kNone, kCauchy, kHuber, kTukey };

double KernelScale(Kernel kernel) {
  return kernel == Kernel::kTukey ? 0.3 : 0.1;
}

std::unique_ptr<ceres::LossFunction> MakeKernel(Kernel kernel) {
  switch (kernel) {
    case Kernel::kCauchy:
      return std::make_unique<ceres::CauchyLoss>(KernelScale(kernel));
    case Kernel::kHuber:
      return std::make_unique<ceres::HuberLoss>(KernelScale(kernel));
    case Kernel::kTukey:
      return std::make_unique<ceres::TukeyLoss>(KernelScale(kernel));
    case Kernel::kNone:
      break;
  }
  return nullptr;
}

BeamKernel MakeBeamKernel(Kernel kernel) {
  switch (kernel) {
    case Kernel::kCauchy:
      return BeamKernel(RobustKernel::kCauchy, KernelScale(kernel));
    case Kernel::kHuber:
      return BeamKernel(RobustKernel::kHuber, KernelScale(kernel));
    case Kernel::kTukey:
      return BeamKernel(RobustKernel::kTukey, KernelScale(kernel));
    case Kernel::kNone:
      break;
  }
  return {};
}

// Beams of a laser at `truth` seeing random lines, with range noise and a tenth of outliers;
// one beam lies exactly on its line at `at` (a zero residual).
std::vector<BeamTerm> RandomBeams(std::mt19937& rng, const double truth[3], const double at[3]) {
  std::uniform_real_distribution<double> angle(-M_PI, M_PI), distance(1.0, 20.0);
  std::normal_distribution<double> noise(0.0, 0.03);
  std::uniform_real_distribution<double> unit(0.0, 1.0);
  std::vector<BeamTerm> beams;
  for (int k = 0; k < 200; ++k) {
    BeamTerm beam;
    const double bearing = -M_PI / 2 + M_PI * k / 199.0;
    beam.cos_bearing = std::cos(bearing);
    beam.sin_bearing = std::sin(bearing);
    const double phi = truth[2] + bearing;
    const Eigen::Vector2d u(std::cos(phi), std::sin(phi));
    const double range = distance(rng);
    const Eigen::Vector2d hit = Eigen::Vector2d(truth[0], truth[1]) + range * u;
    // A wall through the hit, seen 0–70° off its normal.
    const double tilt = (unit(rng) * 2.0 - 1.0) * 1.2;
    beam.line.normal = -Eigen::Vector2d(std::cos(phi + tilt), std::sin(phi + tilt));
    beam.line.offset = beam.line.normal.dot(hit);
    beam.range_m = range + noise(rng) + (unit(rng) < 0.1 ? 0.5 * unit(rng) : 0.0);
    beams.push_back(beam);
  }
  // The last beam ends exactly on its line when the laser stands at `at`.
  BeamTerm& exact = beams.back();
  const double phi = at[2] + std::atan2(exact.sin_bearing, exact.cos_bearing);
  const Eigen::Vector2d u(std::cos(phi), std::sin(phi));
  exact.line.normal = -u;
  exact.line.offset = exact.line.normal.dot(Eigen::Vector2d(at[0], at[1]) + exact.range_m * u);
  return beams;
}

struct Evaluation {
  double cost = 0.0;
  Eigen::Vector3d gradient;
  Eigen::Matrix3d information;  // JᵀJ of the (corrected) Jacobian
};

Evaluation EvaluateProblem(ceres::Problem& problem) {
  Evaluation result;
  std::vector<double> gradient;
  ceres::CRSMatrix jacobian;
  EXPECT_TRUE(problem.Evaluate(ceres::Problem::EvaluateOptions(), &result.cost, nullptr, &gradient,
                               &jacobian));
  result.gradient = Eigen::Vector3d(gradient[0], gradient[1], gradient[2]);
  result.information.setZero();
  for (int row = 0; row < jacobian.num_rows; ++row) {
    Eigen::Vector3d j = Eigen::Vector3d::Zero();
    for (int i = jacobian.rows[row]; i < jacobian.rows[row + 1]; ++i)
      j(jacobian.cols[i]) = jacobian.values[i];
    result.information += j * j.transpose();
  }
  return result;
}

struct Case {
  Kernel kernel;
  bool cosine;
  std::string name;
};

void PrintTo(const Case& c, std::ostream* os) {
  *os << c.name;
}

class BeamsResidualTest : public ::testing::TestWithParam<Case> {};

// The whole point of the fused block: Ceres must see the same cost, gradient and Gauss–Newton
// matrix as with one block per beam, at several postures (near and far from the truth, and where
// one residual is exactly zero), and a solve must end at the same posture.
TEST_P(BeamsResidualTest, MatchesOneBlockPerBeamWithCeresLoss) {
  const Case& c = GetParam();
  std::mt19937 rng(11);
  const double truth[3] = {1.0, -2.0, 0.4};
  const double exact_at[3] = {1.05, -2.02, 0.41};
  const std::vector<BeamTerm> beams = RandomBeams(rng, truth, exact_at);
  const double postures[][3] = {
      {1.0, -2.0, 0.4}, {1.05, -2.02, 0.41}, {1.3, -1.8, 0.5}, {0.8, -2.2, 0.3}};
  for (const auto& start : postures) {
    double fused_pose[3] = {start[0], start[1], start[2]};
    double reference_pose[3] = {start[0], start[1], start[2]};
    ceres::Problem fused;
    BeamsResidual* fused_residual = new BeamsResidual(beams, c.cosine, MakeBeamKernel(c.kernel));
    fused.AddResidualBlock(fused_residual, nullptr, fused_pose);
    ceres::Problem reference;
    for (const BeamTerm& beam : beams)
      reference.AddResidualBlock(new OneBeam(beam, c.cosine), MakeKernel(c.kernel).release(),
                                 reference_pose);
    const std::string where = c.name + " from (" + std::to_string(start[0]) + ", " +
                              std::to_string(start[1]) + ", " + std::to_string(start[2]) + ")";
    const Evaluation a = EvaluateProblem(fused), b = EvaluateProblem(reference);
    EXPECT_NEAR(a.cost, b.cost, 1e-12 * std::max(1.0, b.cost)) << where;
    EXPECT_LT((a.gradient - b.gradient).norm(), 1e-10 * std::max(1.0, b.gradient.norm())) << where;
    EXPECT_LT((a.information - b.information).norm(), 1e-10 * b.information.norm()) << where;

    ceres::Solver::Options options;
    options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
    options.max_num_iterations = 20;
    ceres::Solver::Summary fused_summary, reference_summary;
    ceres::Solve(options, &fused, &fused_summary);
    ceres::Solve(options, &reference, &reference_summary);
    EXPECT_EQ(fused_summary.iterations.size(), reference_summary.iterations.size()) << where;
    for (int i = 0; i < 3; ++i) EXPECT_NEAR(fused_pose[i], reference_pose[i], 1e-9) << where;
    EXPECT_NEAR(fused_summary.final_cost, reference_summary.final_cost,
                1e-12 * std::max(1.0, reference_summary.final_cost))
        << where;
  }
}

// Levenberg–Marquardt's trial steps ask for the cost alone (no Jacobians): that shortcut must
// give the full evaluation's cost, ½‖r‖², at postures near and far from the truth.
TEST_P(BeamsResidualTest, CostOnlyEvaluationGivesTheFullEvaluationsCost) {
  const Case& c = GetParam();
  std::mt19937 rng(17);
  const double truth[3] = {-3.0, 0.5, -1.2};
  const std::vector<BeamTerm> beams = RandomBeams(rng, truth, truth);
  const BeamsResidual residual(beams, c.cosine, MakeBeamKernel(c.kernel));
  const double postures[][3] = {{-3.0, 0.5, -1.2}, {-2.9, 0.45, -1.15}, {-3.4, 0.9, -1.0}};
  for (const auto& pose : postures) {
    const double* parameters[] = {pose};
    double full[BeamsResidual::kResiduals], cost_only[BeamsResidual::kResiduals];
    double jacobian[3 * BeamsResidual::kResiduals];
    double* jacobians[] = {jacobian};
    ASSERT_TRUE(residual.Evaluate(parameters, full, jacobians));
    ASSERT_TRUE(residual.Evaluate(parameters, cost_only, nullptr));
    double full_cost = 0.0, shortcut_cost = 0.0;
    for (int i = 0; i < BeamsResidual::kResiduals; ++i) {
      full_cost += 0.5 * full[i] * full[i];
      shortcut_cost += 0.5 * cost_only[i] * cost_only[i];
    }
    EXPECT_GT(full_cost, 0.0);
    EXPECT_NEAR(shortcut_cost, full_cost, 1e-12 * full_cost) << c.name;
  }
}

// A full evaluation at the posture of the last cost-only one takes the kernel's values from it:
// its residuals and Jacobian must be those of a block that never evaluated a cost, to the bit;
// and a cost-only evaluation elsewhere must not leak into a full one here.
TEST_P(BeamsResidualTest, FullEvaluationAfterTheCostIsBitForBitAFreshOne) {
  const Case& c = GetParam();
  std::mt19937 rng(19);
  const double truth[3] = {2.0, 1.0, -0.3};
  const std::vector<BeamTerm> beams = RandomBeams(rng, truth, truth);
  const double here[3] = {2.04, 0.97, -0.29}, elsewhere[3] = {2.1, 1.2, -0.2};
  const BeamsResidual fresh(beams, c.cosine, MakeBeamKernel(c.kernel));
  const BeamsResidual after_cost(beams, c.cosine, MakeBeamKernel(c.kernel));
  const BeamsResidual after_other(beams, c.cosine, MakeBeamKernel(c.kernel));
  const auto full = [](const BeamsResidual& residual, const double pose[3]) {
    const double* parameters[] = {pose};
    std::vector<double> values(BeamsResidual::kResiduals + 3 * BeamsResidual::kResiduals);
    double* jacobians[] = {values.data() + BeamsResidual::kResiduals};
    EXPECT_TRUE(residual.Evaluate(parameters, values.data(), jacobians));
    return values;
  };
  const auto cost_only = [](const BeamsResidual& residual, const double pose[3]) {
    const double* parameters[] = {pose};
    double values[BeamsResidual::kResiduals];
    EXPECT_TRUE(residual.Evaluate(parameters, values, nullptr));
  };
  cost_only(after_cost, here);
  cost_only(after_other, elsewhere);
  const std::vector<double> expected = full(fresh, here);
  EXPECT_EQ(full(after_cost, here), expected) << c.name;
  EXPECT_EQ(full(after_other, here), expected) << c.name;
  EXPECT_EQ(full(after_cost, here), expected) << c.name << " (twice)";
}

INSTANTIATE_TEST_SUITE_P(KernelsAndWeightings, BeamsResidualTest,
                         ::testing::Values(Case{Kernel::kCauchy, true, "cauchy_cosine"},
                                           Case{Kernel::kCauchy, false, "cauchy_plain"},
                                           Case{Kernel::kHuber, true, "huber_cosine"},
                                           Case{Kernel::kTukey, true, "tukey_cosine"},
                                           Case{Kernel::kNone, true, "no_kernel_cosine"}),
                         [](const auto& test_info) { return test_info.param.name; });

TEST(BeamsResidual, ShowsCeresFourResidualsWhateverTheBeamCount) {
  std::mt19937 rng(3);
  const double truth[3] = {0.0, 0.0, 0.0};
  const std::vector<BeamTerm> beams = RandomBeams(rng, truth, truth);
  EXPECT_EQ(BeamsResidual(beams, true).num_residuals(), 4);
  EXPECT_EQ(BeamsResidual(beams, true, MakeBeamKernel(Kernel::kCauchy)).num_residuals(), 4);
}

// Beams that all see one wall head-on leave the posture free along the wall: the Gauss–Newton
// matrix is singular there. The direction without information gets a zero residual and row,
// and the cost, gradient and matrix stay the beams' own.
TEST(BeamsResidual, ADirectionWithoutInformationKeepsTheBeamsCostAndGradient) {
  std::vector<BeamTerm> beams;
  for (int k = 0; k < 9; ++k) {
    BeamTerm beam;  // bearing 0: every beam runs along x onto the wall x = 2 + k·1 cm noise
    beam.range_m = 2.0 + 0.01 * (k % 3);
    beam.line.normal = Eigen::Vector2d(-1.0, 0.0);
    beam.line.offset = -2.0;
    beams.push_back(beam);
  }
  for (const bool with_kernel : {false, true}) {
    double fused_pose[3] = {0.03, 0.5, 0.0}, reference_pose[3] = {0.03, 0.5, 0.0};
    ceres::Problem fused, reference;
    fused.AddResidualBlock(
        new BeamsResidual(beams, true,
                          with_kernel ? MakeBeamKernel(Kernel::kCauchy) : BeamKernel()),
        nullptr, fused_pose);
    for (const BeamTerm& beam : beams)
      reference.AddResidualBlock(new OneBeam(beam, true),
                                 with_kernel ? new ceres::CauchyLoss(0.1) : nullptr,
                                 reference_pose);
    const Evaluation a = EvaluateProblem(fused), b = EvaluateProblem(reference);
    EXPECT_NEAR(a.cost, b.cost, 1e-14) << "kernel " << with_kernel;
    EXPECT_LT((a.gradient - b.gradient).norm(), 1e-12) << "kernel " << with_kernel;
    EXPECT_LT((a.information - b.information).norm(), 1e-12) << "kernel " << with_kernel;
    EXPECT_GT(a.cost, 0.0);
  }
}

// The refinement's kernels replace Ceres' loss functions inside the beams' block: they must give
// the very same bits, from zero through the kernels' bends to far outliers, or the refinement's
// steps (and every session's output) would move.
TEST(BeamKernel, EvaluatesToTheBitAsCeresLossFunctions) {
  std::mt19937 rng(8);
  std::uniform_real_distribution<double> exponent(-12.0, 3.0);
  std::vector<double> squares = {0.0, 0.01, 0.09, 0.0100000001, 0.0899999999, 1.0};
  for (int i = 0; i < 2000; ++i) squares.push_back(std::pow(10.0, exponent(rng)));
  for (const Kernel kernel : {Kernel::kCauchy, Kernel::kHuber, Kernel::kTukey}) {
    const std::unique_ptr<ceres::LossFunction> reference = MakeKernel(kernel);
    const BeamKernel inline_kernel = MakeBeamKernel(kernel);
    for (const double s : squares) {
      double expected[3], got[3];
      reference->Evaluate(s, expected);
      inline_kernel.Evaluate(s, got);
      for (int k = 0; k < 3; ++k)
        ASSERT_EQ(got[k], expected[k])
            << "kernel " << static_cast<int>(kernel) << " s " << s << " derivative " << k;
      double derivatives[3];
      inline_kernel.Derivatives(s, derivatives);
      ASSERT_EQ(derivatives[1], expected[1]) << "kernel " << static_cast<int>(kernel) << " s " << s;
      ASSERT_EQ(derivatives[2], expected[2]) << "kernel " << static_cast<int>(kernel) << " s " << s;
    }
  }
  double none[3];
  BeamKernel().Evaluate(0.25, none);
  EXPECT_EQ(none[0], 0.25);
  EXPECT_EQ(none[1], 1.0);
  EXPECT_EQ(none[2], 0.0);
  EXPECT_FALSE(BeamKernel().robust());
}

TEST(BeamsResidual, FailsWhenAPlainResidualRunsAlongItsLine) {
  BeamTerm beam;  // bearing 0, so from heading 0 the beam runs along x
  beam.range_m = 1.0;
  beam.line.normal = Eigen::Vector2d(0.0, 1.0);
  beam.line.offset = 1.0;
  const BeamsResidual residual({beam}, false);
  const double pose[3] = {0.0, 0.0, 0.0};
  const double* parameters[] = {pose};
  double values[BeamsResidual::kResiduals] = {};
  EXPECT_FALSE(residual.Evaluate(parameters, values, nullptr));
  const BeamsResidual cosine({beam}, true);
  EXPECT_TRUE(cosine.Evaluate(parameters, values, nullptr));
  // The end point (1, 0) lies 1 m below the line y = 1: a squared residual of 1 in all.
  double squared = 0.0;
  for (const double value : values) squared += value * value;
  EXPECT_NEAR(squared, 1.0, 1e-12);
}

}  // namespace
}  // namespace scanloc
