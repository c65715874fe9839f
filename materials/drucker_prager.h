// Drucker-Prager with exponential strain softening (Blatny et al. 2021; physics.md 4.1) for
// rock, ice and saturated debris.
//
//   y(p, q) = q - gamma(phi) (p + c),   gamma = 6 sin(phi) / (3 - sin(phi))
//   phi(e) = phi_res + (phi_ini - phi_res) exp(-chi e),   c(e) = c_ini exp(-chi e)
//
// e is the accumulated deviatoric plastic Hencky strain. The flow is non-associative and
// volume preserving: p is kept and the deviatoric strain shrinks; beyond the tension tip the
// state goes to the tip (p = -c, q = 0). The return is consistent: the surface it lands on is
// the one of the updated e (solved by a safeguarded Newton iteration), so the mapping is
// idempotent and chi = 1e10 (strength lost on first yield) is handled without special cases.
#pragma once

#include "materials/hencky.h"

#include <cmath>

namespace talus {

struct DruckerPragerParams {
  double frictionAngle = 30.0 * M_PI / 180;         ///< phi_ini (rad)
  double residualFrictionAngle = 30.0 * M_PI / 180; ///< phi_res (rad)
  double cohesion = 0;                              ///< c_ini (Pa, pressure units: tension tip at p = -c)
  double softening = 0;                             ///< chi
};

struct DruckerPragerModel {
  static constexpr const char* kName = "drucker_prager";
  struct State {
    float plasticStrain = 0; ///< accumulated deviatoric plastic Hencky strain e
  };

  HenckyElasticity elastic;
  DruckerPragerParams params;

  static double gammaOf(double phi) {
    const double s = std::sin(phi);
    return 6 * s / (3 - s);
  }
  double frictionAngle(double e) const {
    return params.residualFrictionAngle + (params.frictionAngle - params.residualFrictionAngle) * std::exp(-params.softening * e);
  }
  double cohesion(double e) const { return params.cohesion * std::exp(-params.softening * e); }

  /// Yield function of principal Hencky strains at accumulated plastic strain e (Pa).
  double yield(const Vec3d& eps, double e) const {
    const double tr = eps.sum();
    const double p = -elastic.bulk() * tr;
    const double q = std::sqrt(1.5) * 2 * elastic.mu * (eps - Vec3d::Constant(tr / 3)).norm();
    return q - gammaOf(frictionAngle(e)) * (p + cohesion(e));
  }

  Vec3d stress(const Vec3d& eps, const State&) const { return elastic.stress(eps); }
  double waveSpeed(double rho) const { return elastic.waveSpeed(rho); }

  /// Return mapping; true when eps was changed (plastic step).
  bool project(Vec3d& eps, State& s) const {
    const double K = elastic.bulk(), k = std::sqrt(1.5) * 2 * elastic.mu;
    const double tr = eps.sum(), p = -K * tr;
    const Vec3d dev = eps - Vec3d::Constant(tr / 3);
    const double a = dev.norm(); // |dev eps|, q = k a
    const double e0 = s.plasticStrain;
    if (k * a - gammaOf(frictionAngle(e0)) * (p + cohesion(e0)) <= 0) return false;

    // Beyond the tip even once all deviatoric strain is removed: go to the tip.
    if (p + cohesion(e0 + a) <= 0) {
      eps = Vec3d::Constant(cohesion(e0 + a) / (3 * K));
      s.plasticStrain = float(e0 + a);
      return true;
    }
    // h(d) = k (a - d) - gamma(e0 + d) (p + c(e0 + d)): h(0) > 0 >= h(a); find its root.
    auto h = [&](double d, double& dh) {
      const double e = e0 + d, phi = frictionAngle(e), c = cohesion(e);
      const double sphi = std::sin(phi), g = 6 * sphi / (3 - sphi);
      const double dg = 18 * std::cos(phi) / ((3 - sphi) * (3 - sphi)) *
                        (-params.softening * (params.frictionAngle - params.residualFrictionAngle) *
                         std::exp(-params.softening * e));
      const double dc = -params.softening * c;
      dh = -k - dg * (p + c) - g * dc;
      return k * (a - d) - g * (p + c);
    };
    double lo = 0, hi = a, dh;
    // Start from the explicit return (exact when chi = 0).
    double d = std::clamp(a - gammaOf(frictionAngle(e0)) * (p + cohesion(e0)) / k, 0.0, a);
    for (int it = 0; it < 60; ++it) {
      const double f = h(d, dh);
      if (std::abs(f) <= 1e-12 * k * a) break;
      (f > 0 ? lo : hi) = d;
      double next = d - f / dh;
      if (!(next > lo && next < hi)) next = 0.5 * (lo + hi); // Newton left the bracket: bisect
      if (hi - lo <= 1e-15 * a) break;
      d = next;
    }
    eps = Vec3d::Constant(tr / 3) + (a > 0 ? (a - d) / a : 0.0) * dev;
    s.plasticStrain = float(e0 + d);
    return true;
  }
};

} // namespace talus
