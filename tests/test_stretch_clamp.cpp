// Extreme compression and inverted deformation gradients are clamped, not propagated as NaN.
#include "materials/elastic.h"
#include "materials/hencky.h"

#include <Eigen/SVD>

#include <gtest/gtest.h>

using namespace talus;

TEST(StretchClamp, InvertedAndCrushedDeformationGradientsStayFiniteAndClamped) {
  ElasticModel m;
  m.elastic = HenckyElasticity::fromYoung(1e6, 0.3);
  ElasticModel::State s;
  const Mat3d cases[] = {
      Vec3d(1, 1, -0.5).asDiagonal(),     // inverted along z
      Vec3d(1e-4, 1, 1).asDiagonal(),      // crushed to 1e-4
      Vec3d(100, 1, 1).asDiagonal(),       // stretched 100x
      Mat3d::Zero(),                       // degenerate
  };
  for (const Mat3d& F : cases) {
    Mat3 Fout;
    Sym3 tau;
    updateSolid(m, F, s, Fout, tau, 1e-3);
    ASSERT_TRUE(Fout.allFinite());
    ASSERT_TRUE(tau.matrix().allFinite());
    const Eigen::JacobiSVD<Mat3d> svd(Fout.cast<double>());
    EXPECT_GE(svd.singularValues().minCoeff(), kMinStretch * (1 - 1e-5));
    EXPECT_LE(svd.singularValues().maxCoeff(), kMaxStretch * (1 + 1e-5));
    EXPECT_GT(Fout.cast<double>().determinant(), 0.0); // the clamp also undoes the inversion
  }
}
