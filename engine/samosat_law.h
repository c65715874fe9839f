// samosAT basal friction, AvaFrame com1DFA's default law (Sampl 2007; AvaFrame
// docs/theoryCom1DFA.rst, eq. "SamosAT friction model", and its implementation SamosATfric in
// com1DFA/DFAToolsCython.pyx):
//
//   tau = tau0 + mu (1 + Rs0 / (Rs0 + Rs)) sigma + rho u^2 / ((1/kappa) ln(h/R) + B)^2,
//   Rs = rho u^2 / (sigma + 0.001 Pa),  ln(h/R) >= 0
//
// with AvaFrame's defaults mu 0.155, tau0 0, Rs0 0.222, kappa 0.43, R 0.05 m, B 4.13. At rest the
// Coulomb part is twice mu sigma; fast flow (Rs >> Rs0) lowers it to mu sigma while the turbulent
// part grows. On grid nodes, as for Voellmy: sigma = rho g_n h is the basal normal stress of the
// flow above (AvaFrame's, without its curvature term), the shear over it is carried by the
// normal impulse the contact removes, and the step is integrated implicitly.
#pragma once

#include "engine/contact_law.h"

#include <algorithm>
#include <cmath>

namespace talus {

struct SamosAtLaw {
  static constexpr const char* kName = "samosat";
  static constexpr bool kNeedsThickness = true;
  static std::vector<std::string> parameterNames() { return {"friction", "min_shear", "rs0", "kappa", "roughness", "b"}; }
  std::vector<double> values() const { return {double(mu), double(tau0), double(rs0), double(kappa), double(roughness), double(b)}; }
  Real mu = Real(0.155), tau0 = 0, rs0 = Real(0.222), kappa = Real(0.43), roughness = Real(0.05), b = Real(4.13);

  /// tau / sigma at speed u for basal normal stress sigma (Pa), density rho and thickness h.
  /// What does not depend on u (the logarithm above all) is computed once per node: the implicit
  /// solve evaluates the shear and its slope a few times per node.
  struct Shear {
    double mu, rs0, rho, minShearOverSigma, sigmaPlus, turbulentDenominator;
    Shear(double sigma, double rho, double h, const double p[6])
        : mu(p[0]), rs0(p[2]), rho(rho), minShearOverSigma(p[1] / sigma), sigmaPlus(sigma + 0.001) {
      const double div = std::log(std::max(h / p[4], 1.0)) / p[3] + p[5];
      turbulentDenominator = div * div * sigma;
    }
    double operator()(double u) const {
      const double rs = rho * u * u / sigmaPlus;
      return minShearOverSigma + mu * (1 + rs0 / (rs0 + rs)) + rho * u * u / turbulentDenominator;
    }
    /// d/du of the above.
    double slope(double u) const {
      const double rs = rho * u * u / sigmaPlus, r = rs0 + rs;
      return 2 * rho * u * (1 / turbulentDenominator - mu * rs0 / (r * r * sigmaPlus));
    }
  };
  static double shearOverNormal(double u, double sigma, double rho, double h, const double p[6]) {
    return Shear(sigma, rho, h, p)(u);
  }

  void apply(ContactNode& c, const ContactStep& s) const {
    double p[6] = {mu, tau0, rs0, kappa, roughness, b};
    if (c.params)
      for (int i = 0; i < 6; ++i) p[i] = c.params[i];
    const double gn = -double(s.gravity.dot(c.n));
    const double sigma = double(c.rho) * gn * double(c.h);
    if (!(sigma > 0)) { // no hydrostatic support (a wall, an overhang): the Coulomb part alone
      slideImplicitly(c, [&](double) { return p[0]; }, [](double) { return 0.0; });
      return;
    }
    const Shear shear(sigma, double(c.rho), double(c.h), p);
    slideImplicitly(c, shear, [&](double u) { return shear.slope(u); });
  }
};

} // namespace talus
