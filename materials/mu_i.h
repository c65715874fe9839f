// μ(I) rheology of dense granular flow (Jop, Forterre & Pouliquen 2006, Nature 441) as a
// Drucker-Prager cone whose friction grows with the inertial number:
//
//   q = sqrt(3) mu(I) p,   mu(I) = mu_s + (mu_2 - mu_s) I / (I0 + I),   I = gdot d / sqrt(p / rho_s)
//
// (tau = q / sqrt(3) is the equivalent shear stress, gdot = sqrt(2) |D_p| the equivalent shear
// rate of the plastic strain rate D_p). The return is implicit in the plastic strain rate, as
// Dunatunga & Kamrin (2015) do: the deviatoric plastic strain x removed this step sets gdot =
// sqrt(2) x / dt, and the yield condition k (a - x) = sqrt(3) p mu(I(x)) is, after multiplying by
// (I0 + I), a quadratic in x with exactly one root in [0, a]; solved in closed form, it is stable
// at large I (mu -> mu_2) and as p -> 0 (I -> infinity, the same limit). No tension: at p <= 0 the
// state goes to the stress-free tip. Flow is volume preserving, as in drucker_prager.h.
#pragma once

#include "materials/hencky.h"

#include <cmath>
#include <limits>
#include <string>
#include <vector>

namespace talus {

/// Defaults: Jop et al. 2006's glass beads (mu_s = tan 20.9 deg, mu_2 = tan 32.76 deg, I0 = 0.279,
/// d = 0.5 mm, rho_s = 2450 kg/m3).
struct MuIParams {
  double muS = 0.3819;        ///< static friction coefficient mu_s
  double mu2 = 0.6435;        ///< limiting friction coefficient mu_2 (> mu_s)
  double i0 = 0.279;          ///< I0
  double grainDiameter = 5e-4; ///< d (m)
  double grainDensity = 2450; ///< rho_s (kg/m3)
};

struct MuIModel {
  static constexpr const char* kName = "mu_i";
  struct State {
    float plasticStrain = 0; ///< accumulated deviatoric plastic Hencky strain
    // The inertial number is not stored: the return leaves the stress on the cone of this step's
    // I, so inertialFromStress reads it back (4 bytes a particle: 128 in all, issue 36).
  };

  HenckyElasticity elastic;
  MuIParams params;

  /// mu(I), and I from a plastic shear rate at Cauchy pressure p.
  double mu(double I) const { return params.muS + (params.mu2 - params.muS) * I / (params.i0 + I); }
  double inertialNumber(double gammaDot, double p) const {
    return gammaDot * params.grainDiameter / std::sqrt(p / params.grainDensity);
  }

  Vec3d stress(const Vec3d& eps, const State&) const { return elastic.stress(eps); }
  double waveSpeed(double rho) const { return elastic.waveSpeed(rho); }
  static std::vector<std::string> stateScalarNames() { return {"plastic_strain", "inertial_number"}; }
  float stateScalar(const State& s, const Sym3& tau, size_t k) const {
    return k == 0 ? s.plasticStrain : float(inertialFromStress(tau));
  }

  /// The inertial number of the step that left Kirchhoff stress tau: mu = q / (sqrt(3) p) inverted,
  /// I = I0 (mu - mu_s) / (mu_2 - mu); 0 inside the static cone (not flowing) or at p <= 0 (the
  /// tip). From a float stress its error is about 1e-7 I0 / (mu_2 - mu), 1e-7 near mu_s.
  double inertialFromStress(const Sym3& tau) const {
    const double p = -(double(tau.xx) + double(tau.yy) + double(tau.zz)) / 3;
    if (!(p > 0)) return 0;
    const double dx = tau.xx + p, dy = tau.yy + p, dz = tau.zz + p;
    const double dev2 = dx * dx + dy * dy + dz * dz +
                        2 * (double(tau.xy) * tau.xy + double(tau.xz) * tau.xz + double(tau.yz) * tau.yz);
    const double mu = std::sqrt(1.5 * dev2) / (std::sqrt(3.0) * p);
    if (mu <= params.muS) return 0;
    if (mu >= params.mu2) return std::numeric_limits<double>::infinity(); // only by rounding: I -> infinity
    return params.i0 * (mu - params.muS) / (params.mu2 - mu);
  }

  /// Return mapping at time step dt; true when eps was changed.
  bool project(Vec3d& eps, State& s, double dt) const {
    const double K = elastic.bulk(), k = std::sqrt(1.5) * 2 * elastic.mu;
    const double tr = eps.sum(), pK = -K * tr;
    const Vec3d dev = eps - Vec3d::Constant(tr / 3);
    const double a = dev.norm(); // q = k a (Kirchhoff)
    const double sq3 = std::sqrt(3.0);
    if (pK <= 0) { // no confinement: the stress-free tip
      eps.setZero();
      s.plasticStrain += float(a);
      return true;
    }
    if (k * a <= sq3 * params.muS * pK) return false;
    // I = c x with c = sqrt(2) d / (dt sqrt(p / rho_s)); p is the Cauchy pressure (Kirchhoff / J).
    const double p = pK * std::exp(-tr);
    const double c = std::sqrt(2.0) * params.grainDiameter / (dt * std::sqrt(p / params.grainDensity));
    // k (a - x) (I0 + c x) = sqrt(3) pK (mu_s I0 + mu_2 c x):  A x^2 + B x + C = 0, C < 0 < A.
    const double A = k * c, B = k * params.i0 - k * a * c + sq3 * pK * params.mu2 * c;
    const double C = params.i0 * (sq3 * pK * params.muS - k * a);
    const double disc = std::sqrt(B * B - 4 * A * C);
    double x = B >= 0 ? -2 * C / (B + disc) : (disc - B) / (2 * A); // the positive root, no cancellation
    x = std::min(std::max(x, 0.0), a);
    eps = Vec3d::Constant(tr / 3) + (a > 0 ? (a - x) / a : 0.0) * dev;
    s.plasticStrain += float(x);
    return true;
  }
};

} // namespace talus
