// St. Venant-Kirchhoff elasticity in Hencky (logarithmic) strain, and the solid update every
// elastoplastic model shares (physics.md section 3).
#pragma once

#include "engine/svd3.h"
#include "engine/sym_eigen3.h"
#include "engine/types.h"

#include <algorithm>
#include <cmath>

namespace talus {

/// Singular values of the trial elastic deformation gradient are clamped to this range before
/// taking logarithms. It only acts on states no physical material here reaches (a 20x
/// compression or stretch along one axis) or on inverted elements (s3 <= 0, where the
/// logarithm does not exist): the clamp keeps such particles finite and is counted as plastic
/// deformation, so the run continues instead of producing NaN.
constexpr double kMinStretch = 0.05;
constexpr double kMaxStretch = 20.0;

struct HenckyElasticity {
  double mu = 0, lambda = 0;

  static HenckyElasticity fromYoung(double E, double nu) {
    return {E / (2 * (1 + nu)), E * nu / ((1 + nu) * (1 - 2 * nu))};
  }
  double bulk() const { return lambda + 2.0 * mu / 3.0; }
  /// Principal Kirchhoff stress of principal Hencky strains.
  Vec3d stress(const Vec3d& eps) const { return 2 * mu * eps + Vec3d::Constant(lambda * eps.sum()); }
  /// P-wave speed sqrt((lambda + 2 mu) / rho).
  double waveSpeed(double rho) const { return std::sqrt((lambda + 2 * mu) / rho); }
};

/// Kirchhoff invariants of principal Hencky strains: p = -K tr(eps) (compression positive),
/// q = sqrt(3/2) 2 mu |dev eps|.
inline double henckyPressure(const HenckyElasticity& e, const Vec3d& eps) { return -e.bulk() * eps.sum(); }

/// One solid particle update: F_trial -> principal Hencky strains -> model.project (return
/// mapping) -> F^E and Kirchhoff stress. `Model` provides State, project(eps, state) and
/// stress(eps, state).
///
/// Only the left stretch matters for an isotropic model, so the usual path diagonalises
/// b = F F^T = U S^2 U^T (a Jacobi symmetric eigen-solve, several times cheaper than an SVD) and rebuilds a projected F^E = U exp(eps_new) V^T as U diag(exp(eps_new) / S) U^T F_trial.
/// Inverted or degenerate F (det <= 0), where b hides the reflection, takes the signed SVD.
template <class Model>
inline void updateSolid(const Model& model, const Mat3d& Ftrial, typename Model::State& state,
                        Mat3& Fout, Sym3& tau) {
  Mat3d U;
  Vec3d stretch;
  const double J = Ftrial.determinant();
  if (J > 1e-12) {
    Vec3d lambda;
    symmetricEigen3(Ftrial * Ftrial.transpose(), lambda, U);
    stretch = lambda.cwiseMax(0.0).cwiseSqrt();
  } else {
    const Svd3 d = svd3(Ftrial);
    U = d.U;
    stretch = d.s; // the last one is <= 0 here: clamped below
  }
  Vec3d eps, clamped;
  bool modified = false;
  for (int i = 0; i < 3; ++i) {
    clamped[i] = std::clamp(stretch[i], kMinStretch, kMaxStretch);
    modified |= clamped[i] != stretch[i];
    eps[i] = std::log(clamped[i]);
  }
  modified |= model.project(eps, state);
  if (modified) {
    if (J > 1e-12) {
      const Vec3d r(std::exp(eps[0]) / stretch[0], std::exp(eps[1]) / stretch[1], std::exp(eps[2]) / stretch[2]);
      Fout = (U * r.asDiagonal() * U.transpose() * Ftrial).cast<Real>();
    } else {
      const Svd3 d = svd3(Ftrial);
      const Vec3d e(std::exp(eps[0]), std::exp(eps[1]), std::exp(eps[2]));
      Fout = (d.U * e.asDiagonal() * d.V.transpose()).cast<Real>();
    }
  } else {
    Fout = Ftrial.cast<Real>();
  }
  const Vec3d t = model.stress(eps, state);
  tau = Sym3::fromMatrix(U * t.asDiagonal() * U.transpose());
}

} // namespace talus
