// Contact laws: how a grid node inside a collider moves relative to it (physics.md section 6).
//
// A law sees the nodes of one block that touch one collider and replaces their velocities
// relative to the collider. The engine calls it once per (block, collider), never per node, and
// each law's own loop is compiled inline (ContactLawOf), so a plain Coulomb node costs what a
// hard-coded Coulomb branch would. A law is one small type with `kName` and
// `apply(ContactNode&, const ContactStep&) const` (engine/contact_laws.h has the basic ones) and
// one row in the scene's law table (io/scene/contact_law_table.cpp).
#pragma once

#include "engine/types.h"

#include <cmath>
#include <memory>
#include <string>
#include <vector>

namespace talus {

/// One grid node in contact with a collider, as a contact law sees it.
struct ContactNode {
  Vec3 v;    ///< velocity relative to the collider (m/s); the law replaces it
  Vec3 n;    ///< outward unit normal of the collider at the node
  Real mass; ///< node mass (kg)
  /// Filled only for laws that ask (needsThickness): the flow thickness along the normal over
  /// the node (m) and the density of the material there (kg/m3).
  Real h = 0, rho = 0;
  /// Per-node values of the law's parameters (a region raster or polygon), or null: the law's own.
  const float* params = nullptr;
};

/// What a law may need of the step besides the node.
struct ContactStep {
  Real dt = 0;
  Vec3 gravity = Vec3::Zero(); ///< this step's gravity (m/s2)
};

class ContactLaw {
public:
  virtual ~ContactLaw() = default;
  virtual const char* name() const = 0;
  /// Applies the law to `count` contact nodes of one block.
  virtual void apply(ContactNode* nodes, int count, const ContactStep& step) const = 0;
  /// Whether apply() reads ContactNode::h and rho (the grid then measures the flow thickness).
  virtual bool needsThickness() const { return false; }
  /// Names of the parameters a region may set per node, in ContactNode::params order.
  virtual std::vector<std::string> parameterNames() const { return {}; }
  /// The law's own values of those parameters (what a region leaves unchanged).
  virtual std::vector<double> parameterValues() const { return {}; }
};

/// A law type as a ContactLaw: one virtual call per block, the per-node loop inlined.
template <class Law>
class ContactLawOf final : public ContactLaw {
public:
  explicit ContactLawOf(const Law& law) : law_(law) {}
  const char* name() const override { return Law::kName; }
  void apply(ContactNode* nodes, int count, const ContactStep& step) const override {
    for (int i = 0; i < count; ++i) law_.apply(nodes[i], step);
  }
  bool needsThickness() const override { return Law::kNeedsThickness; }
  std::vector<std::string> parameterNames() const override { return Law::parameterNames(); }
  std::vector<double> parameterValues() const override { return law_.values(); }
  const Law& law() const { return law_; }

private:
  Law law_;
};

template <class Law>
std::shared_ptr<const ContactLaw> makeContactLaw(const Law& law) {
  return std::make_shared<ContactLawOf<Law>>(law);
}

/// The basal shear of a rate-dependent law, integrated implicitly. The normal velocity into the
/// collider is removed; that removal dvn is the node's share of the basal normal impulse per unit
/// mass (sigma dt / (rho h) over a plug), so a law whose shear is tau = muEff(u) sigma slows the
/// tangential speed u_t to the root of u = u_t - muEff(u) dvn in [0, u_t]: it never reverses
/// the node within a step. `muEff` is the shear over the normal stress at speed u, `slope` its
/// derivative d muEff / du (analytic: the solve runs at every contact node of every step).
template <class MuEff, class Slope>
inline void slideImplicitly(ContactNode& c, MuEff&& muEff, Slope&& slope) {
  const Real vn = c.v.dot(c.n);
  if (vn >= 0) return; // separating: no contact stress
  const Vec3 vt = c.v - vn * c.n;
  const double ut = double(vt.norm()), dvn = -double(vn);
  if (ut <= muEff(0.0) * dvn) {
    c.v.setZero(); // the static part holds
    return;
  }
  // f(u) = u - ut + muEff(u) dvn rises from f(0) < 0 to f(ut) > 0: safeguarded Newton. The
  // node's velocity is stored in float (Real), so 1e-8 of ut is below its last bit.
  double lo = 0, hi = ut, u = ut - muEff(ut) * dvn;
  if (!(u > lo && u < hi)) u = 0.5 * (lo + hi);
  for (int it = 0; it < 50; ++it) {
    const double f = u - ut + muEff(u) * dvn;
    if (f > 0) hi = u;
    else lo = u;
    const double df = 1 + slope(u) * dvn;
    double next = u - f / df;
    if (!(next > lo && next < hi)) next = 0.5 * (lo + hi);
    if (std::abs(next - u) <= 1e-8 * ut) {
      u = next;
      break;
    }
    u = next;
  }
  c.v = Real(u / ut) * vt;
}

} // namespace talus
