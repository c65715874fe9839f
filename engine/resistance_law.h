// Resistance areas (forests, AvaFrame's RES/): a drag added to the terrain's law where a region
// sets `resistance`, AvaFrame com1DFA's
//
//   F = -cResH rho A |u| u,  i.e. a basal shear tau = cResH rho u^2,  du/dt = -cResH u^2 / h
//
// (A a particle's basal area, h the flow thickness; cResH in 1/m, AvaFrame's default 0.01). In
// the units of the basal normal impulse the grid carries (engine/voellmy_law.h) the shear over
// the normal stress rho g_n h is cResH u^2 / (g_n h), so a step slows the tangential speed left by
// the base law to the root of u = u' - k u^2, k = cResH dvn / (g_n h), implicitly: it never
// reverses a node. As AvaFrame, no drag where the flow is faster than kMaxSpeed or thicker than
// kMaxThickness (it breaks the trees), nor where it is both slower than kMinSpeed and thinner than
// kMinThickness (AvaFrame detrains there, which Talus does not: the mass stays in the flow).
//
// The wrapper adds one parameter, `resistance`, after the base law's; it is 0 (no drag) outside
// the regions. It exists only in scenes with resistance regions: others pay nothing.
#pragma once

#include "engine/contact_law.h"

#include <cmath>
#include <memory>

namespace talus {

class ResistedLaw final : public ContactLaw {
public:
  static constexpr double kMaxSpeed = 40, kMaxThickness = 10;  ///< AvaFrame's forestVMax, forestThMax
  static constexpr double kMinSpeed = 6, kMinThickness = 0.6;  ///< forestVMin, forestThMin

  explicit ResistedLaw(std::shared_ptr<const ContactLaw> base)
      : base_(std::move(base)), index_(base_->parameterNames().size()) {}

  const char* name() const override { return base_->name(); }
  bool needsThickness() const override { return true; }
  std::vector<std::string> parameterNames() const override {
    auto n = base_->parameterNames();
    n.push_back("resistance");
    return n;
  }
  std::vector<double> parameterValues() const override {
    auto v = base_->parameterValues();
    v.push_back(0.0);
    return v;
  }
  const ContactLaw& base() const { return *base_; }

  void apply(ContactNode* nodes, int count, const ContactStep& step) const override {
    Real dvn[kBlockNodes]; // the normal speed each node loses: its share of the basal normal impulse
    for (int i = 0; i < count; ++i) dvn[i] = std::max(Real(0), -nodes[i].v.dot(nodes[i].n));
    base_->apply(nodes, count, step);
    for (int i = 0; i < count; ++i) {
      ContactNode& c = nodes[i];
      const double cRes = c.params ? double(c.params[index_]) : 0.0;
      const double gn = -double(step.gravity.dot(c.n)), h = double(c.h);
      if (!(cRes > 0) || !(dvn[i] > 0) || !(gn > 0) || !(h > 0)) continue;
      const Vec3 vn = c.v.dot(c.n) * c.n, vt = c.v - vn;
      const double u = double(vt.norm());
      if (!(u > 0) || u > kMaxSpeed || h > kMaxThickness || (u < kMinSpeed && h < kMinThickness)) continue;
      const double k = cRes * double(dvn[i]) / (gn * h);
      const double slowed = 2 * u / (1 + std::sqrt(1 + 4 * k * u));
      c.v = vn + Real(slowed / u) * vt;
    }
  }

private:
  std::shared_ptr<const ContactLaw> base_;
  size_t index_; ///< position of `resistance` in the node's parameters
};

} // namespace talus
