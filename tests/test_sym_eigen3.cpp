// Cyclic Jacobi eigen-solver for symmetric 3x3 matrices, against reconstruction and Eigen.
#include "engine/sym_eigen3.h"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>
#include <algorithm>
#include <gtest/gtest.h>
#include <random>

using namespace talus;

TEST(SymEigen3, ReconstructsRandomAndNearIdentityMatricesToMachinePrecision) {
  std::mt19937 rng(5);
  std::normal_distribution<double> n(0, 1);
  for (int t = 0; t < 20000; ++t) {
    Eigen::Matrix3d F;
    for (int i = 0; i < 9; ++i) F.data()[i] = n(rng);
    if (t % 2) F = Eigen::Matrix3d::Identity() + std::pow(10.0, -1 - 6 * (t % 7) / 6.0) * F; // MPM-like
    const Eigen::Matrix3d S = F * F.transpose();
    Eigen::Vector3d l;
    Eigen::Matrix3d V;
    symmetricEigen3(S, l, V);
    EXPECT_LT((V * l.asDiagonal() * V.transpose() - S).norm(), 1e-13 * S.norm());
    EXPECT_LT((V.transpose() * V - Eigen::Matrix3d::Identity()).norm(), 1e-13);
    Eigen::Vector3d ref = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(S).eigenvalues();
    std::sort(l.data(), l.data() + 3);
    EXPECT_LT((l - ref).norm(), 1e-13 * S.norm());
  }
}

TEST(SymEigen3, RepeatedEigenvaluesAndDiagonalInput) {
  Eigen::Vector3d l;
  Eigen::Matrix3d V;
  symmetricEigen3(Eigen::Matrix3d::Identity() * 2.0, l, V);
  EXPECT_EQ(l, Eigen::Vector3d(2, 2, 2));
  const Eigen::Matrix3d D = Eigen::Vector3d(3, 1, 1).asDiagonal();
  const Eigen::Matrix3d R = Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  symmetricEigen3(R * D * R.transpose(), l, V);
  EXPECT_LT((V * l.asDiagonal() * V.transpose() - R * D * R.transpose()).norm(), 1e-14);
}
