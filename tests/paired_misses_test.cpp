// A closure's own error is in both chains' misses alike: the paired likelihood tells a perfect
// odometry whose closures err far beyond their stated covariance from an odometry that drifts,
// in heading and in position.

#include "scanloc/graph/paired_misses.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <random>
#include <vector>

namespace scanloc {
namespace {

constexpr double kChi2Of99Percent = 6.635;

// A drive's closures and stretches, in heading or position (K), made like the sparse logs':
// loops of 20–300 m, the matched chain's stated covariance 2e-6 per metre (rad² or m²) and
// understated 5 times, each matched posture jittering by 1e-4 (10 mrad in heading) about the
// chain, each closure stated at 3e-6 and erring as two jittering postures do (8 times its σ), the
// odometry drifting at `odometry_scale` per metre; 60 stretches of 2.5–20 m.
template <int K>
struct Drive {
  std::vector<PairedMiss<K>> closures;
  std::vector<StretchMiss<K>> stretches;
};

template <int K>
Drive<K> MakeDrive(double odometry_scale, int closures, unsigned seed) {
  using Vector = Eigen::Matrix<double, K, 1>;
  using Matrix = Eigen::Matrix<double, K, K>;
  std::mt19937 random(seed);
  std::uniform_real_distribution<double> loop_m(20.0, 300.0);
  std::normal_distribution<double> unit(0.0, 1.0);
  const auto draw = [&](double variance) {
    Vector v;
    for (int i = 0; i < K; ++i) v(i) = std::sqrt(variance) * unit(random);
    return v;
  };
  const double floor = 1e-8, stated_matched = 2e-6, stated_closure = 3e-6, jitter = 1e-4;
  Drive<K> drive;
  for (int i = 0; i < closures; ++i) {
    const double length = loop_m(random);
    const Vector error = draw(stated_closure + 2.0 * jitter);
    PairedMiss<K> m;
    m.odometry_miss = error + draw(odometry_scale * length + floor);
    m.matched_miss = error + draw(5.0 * stated_matched * length);
    m.odometry_known = floor * Matrix::Identity();
    m.odometry_shape = length * Matrix::Identity();
    m.matched_shape = stated_matched * length * Matrix::Identity();
    m.closure_known = stated_closure * Matrix::Identity();
    m.closure_shape = 2.0 * Matrix::Identity();
    drive.closures.push_back(m);
  }
  for (int i = 0; i < 60; ++i) {
    const double length = 2.5 * static_cast<double>(1 << (i % 4));
    StretchMiss<K> m;
    m.miss = draw(odometry_scale * length + floor + 5.0 * stated_matched * length + 2.0 * jitter);
    m.known = floor * Matrix::Identity();
    m.odometry_shape = length * Matrix::Identity();
    m.matched_shape = stated_matched * length * Matrix::Identity();
    m.jitter_shape = 2.0 * Matrix::Identity();
    drive.stretches.push_back(m);
  }
  return drive;
}

// How many of 20 drives (seeds 1–20) give a statistic above χ²₁'s 99 % quantile.
template <int K>
int Rejections(double odometry_scale, int closures) {
  int rejections = 0;
  for (unsigned seed = 1; seed <= 20; ++seed) {
    const Drive<K> drive = MakeDrive<K>(odometry_scale, closures, seed);
    rejections +=
        TestOdometryNoise<K>(drive.closures, drive.stretches).statistic > kChi2Of99Percent;
  }
  return rejections;
}

TEST(PairedMisses, MissesAlikeInBothChainsAreLikelierUnderAClosuresErrorThanOpposite) {
  PairedMiss<1> m;
  m.odometry_known(0, 0) = 1e-8;
  m.odometry_shape(0, 0) = 100.0;
  m.matched_shape(0, 0) = 2e-4;
  m.closure_known(0, 0) = 3e-6;
  m.closure_shape(0, 0) = 2.0;
  const PairedScales closure_errs{0.0, 1.0, 1e-4};
  PairedMiss<1> alike = m, opposite = m;
  alike.odometry_miss(0) = alike.matched_miss(0) = 0.02;
  opposite.odometry_miss(0) = 0.02;
  opposite.matched_miss(0) = -0.02;
  EXPECT_GT(PairedLogLikelihood<1>({alike}, {}, closure_errs),
            PairedLogLikelihood<1>({opposite}, {}, closure_errs) + 1.0);
}

// A boundary test's statistic under the null exceeds χ²₁'s 99 % quantile half as often as χ²₁
// (0.5 %): one drive of 20 allowed.
TEST(PairedMisses, APerfectOdometryWhoseClosuresErrEightSigmaIsNotTakenForNoisyInHeading) {
  EXPECT_LE(Rejections<1>(0.0, 10), 1);
  EXPECT_LE(Rejections<1>(0.0, 3), 1);
}

TEST(PairedMisses, APerfectOdometryWhoseClosuresErrEightSigmaIsNotTakenForNoisyInPosition) {
  EXPECT_LE(Rejections<2>(0.0, 10), 1);
}

// The noisy Radish logs' odometry, about 4e-4 rad²/m, and the Kümmerle logs' (3e-4 and more):
// three closures find it in 18 drives of 20, ten in all.
TEST(PairedMisses, AnOdometryDriftingFourTenThousandthsRadSquaredPerMetreIsFoundByTenClosures) {
  EXPECT_GE(Rejections<1>(4e-4, 3), 18);
  EXPECT_EQ(Rejections<1>(4e-4, 10), 20);
}

TEST(PairedMisses, AnOdometryDriftingInPositionIsFoundByThreeClosures) {
  EXPECT_EQ(Rejections<2>(1e-4, 3), 20);
}

TEST(PairedMisses, NoClosureGivesNoStatistic) {
  const Drive<1> drive = MakeDrive<1>(4e-4, 0, 1);
  EXPECT_EQ(TestOdometryNoise<1>(drive.closures, drive.stretches).statistic, 0.0);
}

}  // namespace
}  // namespace scanloc
