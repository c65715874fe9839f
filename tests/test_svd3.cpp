// Signed 3x3 SVD: reconstruction, rotations, ordering, and inverted matrices.
#include "engine/svd3.h"

#include <gtest/gtest.h>
#include <random>

using namespace talus;

namespace {
void expectValid(const Eigen::Matrix3d& F, const Svd3& d, double tol) {
  const Eigen::Matrix3d R = d.U * d.s.asDiagonal() * d.V.transpose();
  EXPECT_LT((R - F).norm(), tol * std::max(1.0, F.norm()));
  EXPECT_LT((d.U.transpose() * d.U - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  EXPECT_LT((d.V.transpose() * d.V - Eigen::Matrix3d::Identity()).norm(), 1e-12);
  EXPECT_NEAR(d.U.determinant(), 1.0, 1e-12);
  EXPECT_NEAR(d.V.determinant(), 1.0, 1e-12);
  EXPECT_GE(d.s(0), d.s(1));
  EXPECT_GE(d.s(1), std::abs(d.s(2)) - 1e-12 * d.s(0));
  EXPECT_GE(d.s(1), 0.0);
}
} // namespace

TEST(Svd3, RandomMatricesReconstructToMachinePrecision) {
  std::mt19937 rng(7);
  std::normal_distribution<double> n(0, 1);
  for (int t = 0; t < 20000; ++t) {
    Eigen::Matrix3d F;
    for (int i = 0; i < 9; ++i) F.data()[i] = n(rng);
    if (t % 3 == 0) F = Eigen::Matrix3d::Identity() + 0.01 * F; // near identity, the MPM case
    const Svd3 d = svd3(F);
    expectValid(F, d, 1e-12);
    EXPECT_NEAR(d.s.prod(), F.determinant(), 1e-10 * std::max(1.0, std::abs(F.determinant())));
  }
}

TEST(Svd3, InvertedMatrixHasNegativeLastSingularValue) {
  Eigen::Matrix3d F = Eigen::Matrix3d::Identity();
  F(2, 2) = -0.5;
  const Svd3 d = svd3(F);
  expectValid(F, d, 1e-12);
  EXPECT_NEAR(d.s(2), -0.5, 1e-14);
}

TEST(Svd3, DegenerateAndRepeatedSingularValues) {
  const Eigen::Matrix3d cases[] = {Eigen::Matrix3d::Identity(), Eigen::Matrix3d::Zero(),
                                   Eigen::Vector3d(2, 2, 1e-9).asDiagonal(),
                                   Eigen::Vector3d(1e3, 1, 1e-3).asDiagonal()};
  for (const auto& F : cases) expectValid(F, svd3(F), 1e-12);
  // Rank one.
  const Eigen::Vector3d a(1, 2, 3), b(-1, 0.5, 2);
  expectValid(a * b.transpose(), svd3(a * b.transpose()), 1e-12);
}
