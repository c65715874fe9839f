// St. Venant-Kirchhoff elasticity in Hencky (logarithmic) strain, and the solid update every
// elastoplastic model shares (physics.md section 3).
#pragma once

#include "engine/svd3.h"

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
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

namespace detail {

/// Symmetric 3x3 matrix in double: (xx, yy, zz, xy, xz, yz). Products below are only taken
/// between matrices that commute (powers of one matrix), whose product is again symmetric.
struct SymD {
  double xx, yy, zz, xy, xz, yz;
  static SymD of(const Mat3d& m) {
    return {m(0, 0), m(1, 1), m(2, 2), 0.5 * (m(0, 1) + m(1, 0)), 0.5 * (m(0, 2) + m(2, 0)), 0.5 * (m(1, 2) + m(2, 1))};
  }
  Mat3d matrix() const {
    Mat3d m;
    m << xx, xy, xz, xy, yy, yz, xz, yz, zz;
    return m;
  }
  double trace() const { return xx + yy + zz; }
  double norm2() const { return xx * xx + yy * yy + zz * zz + 2 * (xy * xy + xz * xz + yz * yz); }
  SymD operator*(const SymD& b) const { // commuting product
    return {xx * b.xx + xy * b.xy + xz * b.xz, xy * b.xy + yy * b.yy + yz * b.yz, xz * b.xz + yz * b.yz + zz * b.zz,
            xx * b.xy + xy * b.yy + xz * b.yz, xx * b.xz + xy * b.yz + xz * b.zz, xy * b.xz + yy * b.yz + yz * b.zz};
  }
  SymD operator*(double s) const { return {xx * s, yy * s, zz * s, xy * s, xz * s, yz * s}; }
  SymD operator+(const SymD& b) const { return {xx + b.xx, yy + b.yy, zz + b.zz, xy + b.xy, xz + b.xz, yz + b.yz}; }
  SymD plusIdentity(double s) const { return {xx + s, yy + s, zz + s, xy, xz, yz}; }
  SymD inverse() const {
    const double cxx = yy * zz - yz * yz, cxy = xz * yz - xy * zz, cxz = xy * yz - xz * yy;
    const double inv = 1 / (xx * cxx + xy * cxy + xz * cxz);
    return {cxx * inv, (xx * zz - xz * xz) * inv, (xx * yy - xy * xy) * inv, cxy * inv, cxz * inv, (xy * xz - xx * yz) * inv};
  }
};

/// log(b) / 2 for symmetric positive definite b = I + X with |X| <= 0.25, by the atanh series
/// log b = 2 (Y + Y^3/3 + Y^5/5 + ...), Y = X (2I + X)^-1 (|Y| <= |X| / 1.75). The term Y^(2j+1)
/// is at most r2^j of |Y|; terms are added until that bound is below 1e-24 (or 7 terms), a double's
/// last bit. A bound of 1e-12 would still be far below the float the strain ends in and measured
/// 1.5-2 % faster on `talus bench --case box snow`, but it moves results in their last bits (the
/// shipped scenes' checksums), so it waits for a change that re-records them anyway.
inline SymD halfLogNearIdentity(const SymD& X) {
  const SymD Y = X * X.plusIdentity(2).inverse();
  const SymD Y2 = Y * Y;
  const double r2 = Y2.trace(); // |Y|^2
  SymD sum = Y, term = Y;
  double rk = 1;
  for (int k = 3; k <= 15; k += 2) {
    rk *= r2;
    if (rk < 1e-24) break;
    term = term * Y2;
    sum = sum + term * (1.0 / k);
  }
  return sum;
}

/// exp(A) for symmetric A with |A| <= 0.5, by its Taylor series (terms down to 1e-13).
inline SymD expSmall(const SymD& A) {
  const double r = std::sqrt(A.norm2());
  SymD sum = A.plusIdentity(1), term = A;
  double rk = r;
  for (int k = 2; k <= 16; ++k) {
    rk *= r / k;
    if (rk < 1e-13) break;
    term = term * A * (1.0 / k);
    sum = sum + term;
  }
  return sum;
}

} // namespace detail

/// One solid particle update: F_trial -> Hencky strain -> model.project (return mapping) -> F^E
/// and Kirchhoff stress. `Model` provides State, `elastic` (HenckyElasticity), project(eps,
/// state, dt) on principal strains (dt for rate-dependent models), and depends on the strain only
/// through p and q (both models here, Drucker-Prager and Cam Clay, are Lode-angle independent).
///
/// Usual path (elastic strains below ~0.12, i.e. |b - I| <= 0.25): everything stays in tensor
/// form. eps = log(b)/2 by a series; the return is applied to a principal vector with the same
/// trace and deviatoric norm, and its result mapped back as eps_new = tr'/3 I + (|dev'|/|dev|)
/// dev eps; F^E = exp(eps_new - eps) F_trial (the two are coaxial). No eigen-solve: about 4x
/// cheaper than diagonalising b.
/// Otherwise b = F F^T = U S^2 U^T is diagonalised (closed form), the stretches clamped, and
/// F^E = U diag(exp(eps_new) / S) U^T F_trial. Inverted or degenerate F (det <= 0), where b hides
/// the reflection, takes the signed SVD.
template <class Model>
inline void updateSolid(const Model& model, const Mat3d& Ftrial, typename Model::State& state,
                        Mat3& Fout, Sym3& tau, double dt) {
  using detail::SymD;
  const double J = Ftrial.determinant();
  const Mat3d b = Ftrial * Ftrial.transpose();
  const SymD X = SymD::of(b).plusIdentity(-1);
  if (J > 1e-12 && X.norm2() <= 0.0625) {
    const SymD eps = detail::halfLogNearIdentity(X);
    const double tr = eps.trace();
    const SymD dev = eps.plusIdentity(-tr / 3);
    const double a = std::sqrt(dev.norm2());
    Vec3d principal = Vec3d::Constant(tr / 3) + a * Vec3d(1, -1, 0) / std::sqrt(2.0);
    SymD epsNew = eps;
    if (model.project(principal, state, dt)) {
      const double trNew = principal.sum();
      const double aNew = (principal - Vec3d::Constant(trNew / 3)).norm();
      epsNew = (dev * (a > 0 ? aNew / a : 0.0)).plusIdentity(trNew / 3);
      // eps and epsNew are coaxial, so exp(epsNew - eps) is the plastic correction of F.
      Fout = (detail::expSmall(epsNew + eps * -1.0).matrix() * Ftrial).cast<Real>();
    } else {
      Fout = Ftrial.cast<Real>();
    }
    const HenckyElasticity& e = model.elastic;
    const SymD t = (epsNew * (2 * e.mu)).plusIdentity(e.lambda * epsNew.trace());
    tau.xx = Real(t.xx), tau.yy = Real(t.yy), tau.zz = Real(t.zz);
    tau.xy = Real(t.xy), tau.xz = Real(t.xz), tau.yz = Real(t.yz);
    return;
  }

  Mat3d U;
  Vec3d stretch;
  if (J > 1e-12) {
    Eigen::SelfAdjointEigenSolver<Mat3d> es;
    es.computeDirect(b);
    U = es.eigenvectors();
    stretch = es.eigenvalues().cwiseMax(0.0).cwiseSqrt();
  } else {
    const Svd3 d = svd3(Ftrial);
    U = d.U;
    stretch = d.s; // the last one is <= 0 here: clamped below
  }
  Vec3d eps;
  bool modified = false;
  for (int i = 0; i < 3; ++i) {
    const double s = std::clamp(stretch[i], kMinStretch, kMaxStretch);
    modified |= s != stretch[i];
    eps[i] = std::log(s);
  }
  modified |= model.project(eps, state, dt);
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
