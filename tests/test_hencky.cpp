// The Hencky strain's series path (materials/hencky.h) against the eigen-solve it replaces.
#include "materials/hencky.h"

#include <cstdio>
#include <random>

#include <gtest/gtest.h>

using namespace talus;
using detail::SymD;

namespace {
/// log(b) / 2 by diagonalising b: the definition the series must reproduce.
Mat3d halfLogByEigenSolve(const Mat3d& b) {
  Eigen::SelfAdjointEigenSolver<Mat3d> es(b);
  return es.eigenvectors() * (0.5 * es.eigenvalues().array().log()).matrix().asDiagonal() *
         es.eigenvectors().transpose();
}
} // namespace

// Tolerance 1e-11 of |eps| plus 1e-14: 1e-11 is what a series stopped at 1e-12 of |Y| would still
// meet (its remainder is a geometric tail of at most 1.03 times that); the eigen-solve works on
// b = I + X and rounds at ~1e-15 absolute, which is what the 1e-14 allows. Both far below the float
// the strain is stored in (6e-8 relative). A series stopped at 1e-10 fails it (1.26 of the
// tolerance, checked).
TEST(Hencky, SeriesLogarithmMatchesTheEigenSolveUpToTheSeriesRadius) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-1, 1);
  double worst = 0;
  for (int i = 0; i < 20000; ++i) {
    Mat3d A;
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) A(r, c) = u(rng);
    const Mat3d S = 0.5 * (A + A.transpose());
    // |X| from 1e-6 to the series' radius 0.25, log-uniform: rock and snow strains live at 1e-4..1e-1.
    const double size = 0.25 * std::pow(10.0, -5.4 * (0.5 + 0.5 * u(rng)));
    const Mat3d X = size * S / S.norm();
    const SymD eps = detail::halfLogNearIdentity(SymD::of(X));
    const Mat3d exact = halfLogByEigenSolve(Mat3d::Identity() + X);
    worst = std::max(worst, (eps.matrix() - exact).norm() / (1e-11 * exact.norm() + 1e-14));
  }
  EXPECT_LT(worst, 1.0);
  std::printf("worst error / tolerance %.3g\n", worst);
}
