// St. Venant-Kirchhoff elasticity in Hencky (logarithmic) strain, and the solid update every
// elastoplastic model shares (physics.md section 3).
#pragma once

#include "engine/svd3.h"
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

/// One solid particle update: F_trial -> SVD -> Hencky strain -> model.project (return mapping)
/// -> F^E and Kirchhoff stress. `Model` provides State, project(eps, state) and stress(eps, state).
template <class Model>
inline void updateSolid(const Model& model, const Mat3d& Ftrial, typename Model::State& state,
                        Mat3& Fout, Sym3& tau) {
  const Svd3 d = svd3(Ftrial);
  Vec3d eps;
  bool modified = false;
  for (int i = 0; i < 3; ++i) {
    const double s = std::clamp(d.s[i], kMinStretch, kMaxStretch);
    modified |= s != d.s[i];
    eps[i] = std::log(s);
  }
  modified |= model.project(eps, state);
  if (modified) {
    const Vec3d s(std::exp(eps[0]), std::exp(eps[1]), std::exp(eps[2]));
    Fout = (d.U * s.asDiagonal() * d.V.transpose()).cast<Real>();
  } else {
    Fout = Ftrial.cast<Real>();
  }
  const Vec3d t = model.stress(eps, state);
  tau = Sym3::fromMatrix(d.U * t.asDiagonal() * d.U.transpose());
}

} // namespace talus
