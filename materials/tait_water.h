// Weakly compressible water with the Tait equation of state (Becker & Teschner 2007;
// physics.md 4.3):  sigma = -p I + 2 eta dev(D),  p = B (J^-k - 1),  J = rho0 / rho.
//
// Only J = det F is tracked, stored as J - 1 so that single precision resolves pressure to
// ~1e-7 of its value (storing J itself would resolve only B k 6e-8 ~ 130 Pa with B = 3e8).
//
// Negative pressure: by default water carries no tension. A free surface that stretches
// (J > 1) would otherwise pull neighbours along and cavitate spuriously, and a particle that
// drifted to J > 1 would have to be squeezed back before it felt pressure again; so J is
// clamped to the J at which p = -max_tension (default 0: J <= 1, p >= 0).
#pragma once

#include "engine/types.h"

#include <algorithm>
#include <cmath>

namespace talus {

struct TaitWaterModel {
  static constexpr const char* kName = "water";

  double bulk = 3e8;      ///< B (Pa)
  double exponent = 7;    ///< k
  double viscosity = 0;   ///< eta (Pa s), Newtonian
  double maxTension = 0;  ///< largest tension (Pa) the water may carry; 0 = none
  /// Each step, a particle's J becomes the grid's mass-weighted mean of its neighbours' J (the
  /// `smooth_pressure` key): the two particle layers of a cell otherwise drift to pressures 2-10
  /// times apart, a mode the grid does not see (docs/convergence.md, "What the particles next to
  /// the wall carry").
  bool smoothPressure = false;

  double pressure(double J) const { return pressureOfStrain(J - 1); }
  /// p of the volumetric strain dJ = J - 1, without cancellation near dJ = 0.
  double pressureOfStrain(double dJ) const { return bulk * std::expm1(-exponent * std::log1p(dJ)); }
  /// J at which p = -maxTension.
  double maxJ() const { return std::pow(1 - maxTension / bulk, -1 / exponent); }
  /// Sound speed at the reference density and at compression J (dp/drho = k B J^-k / rho).
  double soundSpeed(double rho0, double J = 1) const {
    return std::sqrt(exponent * bulk * std::pow(J, -exponent - 1) / rho0);
  }
  /// J of water at rest under a hydrostatic pressure p.
  double restJ(double p) const { return std::pow(1 + p / bulk, -1 / exponent); }

  /// Advances dJ = J - 1 with the velocity gradient C (J <- J det(I + dt C)) and returns the
  /// Kirchhoff stress tau = J sigma.
  void update(float& dJ, const Mat3& C, double dt, Sym3& tau) const {
    const Mat3d A = dt * C.cast<double>();
    // det(I + A) - 1 by its invariants, exact and free of cancellation for small A.
    const double tr = A.trace();
    const double delta = tr + 0.5 * (tr * tr - (A * A).trace()) + A.determinant();
    // maxJ() is a pow per particle; without tension (the default) it is exactly 1 (pow(1, y) = 1).
    const double dMax = maxTension > 0 ? maxJ() - 1 : 0.0;
    const double d = std::min(double(dJ) + delta + double(dJ) * delta, dMax);
    dJ = float(d);
    const double Jn = 1 + d;
    const double p = pressureOfStrain(d);
    Mat3d t = Mat3d::Identity() * (-Jn * p);
    if (viscosity > 0) {
      const Mat3d D = 0.5 * (C + C.transpose()).cast<double>();
      t += Jn * 2 * viscosity * (D - Mat3d::Identity() * (D.trace() / 3));
    }
    tau = Sym3::fromMatrix(t);
  }
};

} // namespace talus
