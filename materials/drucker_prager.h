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
#include <string>
#include <vector>

namespace talus {

/// How the cone q = gamma (p + c) is fitted to a Mohr-Coulomb friction angle phi.
/// Compression (the paper's gamma = 6 sin phi / (3 - sin phi)) matches MC in triaxial compression;
/// in plane-strain flow with this volume-preserving return, the out-of-plane stress settles at p
/// and the cone acts like MC with sin(phi_eff) = gamma / sqrt(3) (phi = 30 deg acts like 44 deg).
/// PlaneStrain (gamma = sqrt(3) sin phi) matches MC exactly in that case; Extension is the inner cone.
enum class DruckerPragerCone { Compression, PlaneStrain, Extension };

struct DruckerPragerParams {
  double frictionAngle = 30.0 * M_PI / 180;         ///< phi_ini (rad)
  double residualFrictionAngle = 30.0 * M_PI / 180; ///< phi_res (rad)
  double cohesion = 0;                              ///< c_ini (Pa, pressure units: tension tip at p = -c)
  double softening = 0;                             ///< chi
  DruckerPragerCone cone = DruckerPragerCone::Compression;
};

struct DruckerPragerModel {
  static constexpr const char* kName = "drucker_prager";
  struct State {
    float plasticStrain = 0; ///< accumulated deviatoric plastic Hencky strain e
  };

  DruckerPragerModel() : DruckerPragerModel(HenckyElasticity{}, DruckerPragerParams{}) {}
  DruckerPragerModel(const HenckyElasticity& e, const DruckerPragerParams& p) : elastic(e) { setParams(p); }

  HenckyElasticity elastic;
  /// Strength parameters; set through setParams so the cached residual gamma follows them.
  const DruckerPragerParams& params() const { return params_; }
  void setParams(const DruckerPragerParams& p) {
    params_ = p;
    gammaResidual_ = gammaOf(p.residualFrictionAngle, p.cone);
  }

  /// gamma(phi) of the cone fit, and d gamma / d phi.
  static double gammaOf(double phi, DruckerPragerCone cone = DruckerPragerCone::Compression) {
    const double s = std::sin(phi);
    switch (cone) {
    case DruckerPragerCone::PlaneStrain: return std::sqrt(3.0) * s;
    case DruckerPragerCone::Extension: return 6 * s / (3 + s);
    default: return 6 * s / (3 - s);
    }
  }
  static double gammaSlope(double phi, DruckerPragerCone cone) {
    const double s = std::sin(phi), c = std::cos(phi);
    switch (cone) {
    case DruckerPragerCone::PlaneStrain: return std::sqrt(3.0) * c;
    case DruckerPragerCone::Extension: return 18 * c / ((3 + s) * (3 + s));
    default: return 18 * c / ((3 - s) * (3 - s));
    }
  }
  double gamma(double e) const { return gammaOf(frictionAngle(e), params_.cone); }
  double frictionAngle(double e) const {
    return params_.residualFrictionAngle + (params_.frictionAngle - params_.residualFrictionAngle) * std::exp(-params_.softening * e);
  }
  double cohesion(double e) const { return params_.cohesion * std::exp(-params_.softening * e); }

  /// Yield function of principal Hencky strains at accumulated plastic strain e (Pa).
  double yield(const Vec3d& eps, double e) const {
    const double tr = eps.sum();
    const double p = -elastic.bulk() * tr;
    const double q = std::sqrt(1.5) * 2 * elastic.mu * (eps - Vec3d::Constant(tr / 3)).norm();
    return q - gamma(e) * (p + cohesion(e));
  }

  Vec3d stress(const Vec3d& eps, const State&) const { return elastic.stress(eps); }
  double waveSpeed(double rho) const { return elastic.waveSpeed(rho); }
  static std::vector<std::string> stateScalarNames() { return {"plastic_strain"}; }
  float stateScalar(const State& s, const Sym3&, size_t) const { return s.plasticStrain; }

  /// Constant strength (no softening): gamma and c need no trigonometry per particle.
  bool softens() const {
    return params_.softening > 0 && (params_.cohesion > 0 || params_.frictionAngle != params_.residualFrictionAngle);
  }

  /// Return mapping; true when eps was changed (plastic step). Rate-independent: dt unused.
  bool project(Vec3d& eps, State& s, double /*dt*/) const {
    const double K = elastic.bulk(), k = std::sqrt(1.5) * 2 * elastic.mu;
    const double tr = eps.sum(), p = -K * tr;
    const Vec3d dev = eps - Vec3d::Constant(tr / 3);
    const double a = dev.norm(); // |dev eps|, q = k a
    const double e0 = s.plasticStrain;
    if (!softens()) {
      if (k * a - gammaResidual_ * (p + params_.cohesion) <= 0) return false;
      if (p + params_.cohesion <= 0) {
        eps = Vec3d::Constant(params_.cohesion / (3 * K));
        s.plasticStrain = float(e0 + a);
        return true;
      }
      const double aNew = gammaResidual_ * (p + params_.cohesion) / k;
      eps = Vec3d::Constant(tr / 3) + (aNew / a) * dev;
      s.plasticStrain = float(e0 + a - aNew);
      return true;
    }
    if (k * a - gamma(e0) * (p + cohesion(e0)) <= 0) return false;

    // Beyond the tip even once all deviatoric strain is removed: go to the tip.
    if (p + cohesion(e0 + a) <= 0) {
      eps = Vec3d::Constant(cohesion(e0 + a) / (3 * K));
      s.plasticStrain = float(e0 + a);
      return true;
    }
    // h(d) = k (a - d) - gamma(e0 + d) (p + c(e0 + d)): h(0) > 0 >= h(a); find its root.
    auto h = [&](double d, double& dh) {
      const double e = e0 + d, phi = frictionAngle(e), c = cohesion(e);
      const double g = gammaOf(phi, params_.cone);
      const double dg = gammaSlope(phi, params_.cone) *
                        (-params_.softening * (params_.frictionAngle - params_.residualFrictionAngle) *
                         std::exp(-params_.softening * e));
      const double dc = -params_.softening * c;
      dh = -k - dg * (p + c) - g * dc;
      return k * (a - d) - g * (p + c);
    };
    double lo = 0, hi = a, dh;
    // Start from the explicit return (exact when chi = 0).
    double d = std::clamp(a - gamma(e0) * (p + cohesion(e0)) / k, 0.0, a);
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

private:
  DruckerPragerParams params_;
  double gammaResidual_ = 0; ///< gamma of the residual friction angle (the constant-strength fast path)
};

} // namespace talus
