// Voellmy basal friction: tau = mu sigma + rho g u^2 / xi (Voellmy 1955; Salm 1993; the law of
// RAMMS and of AvaFrame's com1DFA `Voellmy`), a Coulomb part and a turbulent drag.
//
// On grid nodes the shear is carried by the normal impulse the contact removes, as the Coulomb
// law does: with the basal normal stress of the flow above, sigma = rho g_n h (g_n = -g.n, h the
// flow thickness along the normal), tau / sigma = mu + g u^2 / (xi g_n h). Over a plug this is
// exactly the depth-averaged law; the drag of a step is integrated implicitly (exact root of a
// quadratic), so a node never reverses. Where gravity does not press the flow onto the surface
// (g_n <= 0: a wall, an overhang) only the Coulomb part acts.
#pragma once

#include "engine/contact_law.h"

namespace talus {

struct VoellmyLaw {
  static constexpr const char* kName = "voellmy";
  static constexpr bool kNeedsThickness = true;
  static std::vector<std::string> parameterNames() { return {"friction", "xi"}; }
  Real mu = Real(0.155);  ///< dry friction coefficient (AvaFrame default)
  Real xi = Real(4000);   ///< turbulent friction (m/s2; AvaFrame default)

  void apply(ContactNode& c, const ContactStep& s) const {
    const double mu = c.params ? c.params[0] : this->mu, xi = c.params ? c.params[1] : this->xi;
    const Real vn = c.v.dot(c.n);
    if (vn >= 0) return;
    const Vec3 vt = c.v - vn * c.n;
    const double ut = double(vt.norm()), dvn = -double(vn);
    const double w = ut - mu * dvn; // after the Coulomb part
    if (w <= 0) {
      c.v.setZero();
      return;
    }
    const double gn = -double(s.gravity.dot(c.n)), g = double(s.gravity.norm());
    // u = w - k u^2 with k = g dvn / (xi g_n h): the positive root, written without cancellation.
    const double k = gn > 0 && c.h > 0 ? g * dvn / (xi * gn * double(c.h)) : 0.0;
    const double u = 2 * w / (1 + std::sqrt(1 + 4 * k * w));
    c.v = Real(u / ut) * vt;
  }
};

} // namespace talus
