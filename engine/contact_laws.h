// The rate-independent contact laws: sticky (no-slip), slip, and Coulomb friction. Slip and
// Coulomb act only on a node moving into the collider; a separating node keeps its velocity.
#pragma once

#include "engine/contact_law.h"

namespace talus {

/// No-slip: the node moves with the collider.
struct StickyLaw {
  static constexpr const char* kName = "sticky";
  static constexpr bool kNeedsThickness = false;
  static std::vector<std::string> parameterNames() { return {}; }
  void apply(ContactNode& c, const ContactStep&) const { c.v.setZero(); }
};

/// Frictionless: the normal velocity into the collider is removed.
struct SlipLaw {
  static constexpr const char* kName = "slip";
  static constexpr bool kNeedsThickness = false;
  static std::vector<std::string> parameterNames() { return {}; }
  void apply(ContactNode& c, const ContactStep&) const {
    const Real vn = c.v.dot(c.n);
    if (vn < 0) c.v -= vn * c.n;
  }
};

/// Coulomb friction: the normal velocity into the collider is removed, and the tangential
/// velocity shrinks by mu times it, stopping when static friction holds:
/// v <- max(0, 1 + mu vn / |vt|) vt.
struct CoulombLaw {
  static constexpr const char* kName = "coulomb";
  static constexpr bool kNeedsThickness = false;
  static std::vector<std::string> parameterNames() { return {"friction"}; }
  Real mu = 0;
  void apply(ContactNode& c, const ContactStep&) const {
    const Real mu = c.params ? Real(c.params[0]) : this->mu;
    const Real vn = c.v.dot(c.n);
    if (vn >= 0) return;
    const Vec3 vt = c.v - vn * c.n;
    const Real vtNorm = vt.norm();
    if (vtNorm <= mu * -vn) c.v.setZero(); // static friction holds
    else c.v = (Real(1) + mu * vn / vtNorm) * vt;
  }
};

} // namespace talus
