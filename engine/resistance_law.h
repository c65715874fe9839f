// Resistance areas (forests, AvaFrame's RES/): a drag added to the terrain's law where a region
// sets `resistance`, AvaFrame com1DFA's
//
//   F = -cResH rho A |u| u,  i.e. a basal shear tau = cResH rho u^2,  du/dt = -cResH u^2 / h
//
// (A a particle's basal area, h the flow thickness; cResH in 1/m, AvaFrame's default 0.01). In
// the units of the basal normal impulse the grid carries (engine/voellmy_law.h) the shear over
// the normal stress rho g_n h is cResH u^2 / (g_n h), so a step slows the tangential speed left by
// the base law to the root of u = u' - k u^2, k = cResH dvn / (g_n h), implicitly: it never
// reverses a node. Where the node's `detrainment` (detK, Pa) is positive, AvaFrame's thresholds
// with detrainment apply (com1DFATools.updateResCoeffFields): the drag acts only where the flow is
// faster than kMinSpeed and thicker than kMinThickness, and not where it is faster than kMaxSpeed
// or thicker than kMaxThickness (it breaks the trees); below either lower threshold the forest
// detrains instead (engine/detrainment.h). Where detK is 0 (AvaFrame's `detrainment = False`) the
// drag acts at every speed and thickness, as AvaFrame's does then.
//
// The wrapper adds two parameters, `resistance` and `detrainment`, after the base law's; both are
// 0 outside the regions (a region with `resistance` gets AvaFrame's detK = 5 Pa unless it says
// otherwise, io/scene/region_reader.cpp). It exists only in scenes with resistance regions: others
// pay nothing.
#pragma once

#include "engine/contact_law.h"

#include <cmath>
#include <memory>

namespace talus {

class ResistedLaw final : public ContactLaw {
public:
  static constexpr double kMaxSpeed = 40, kMaxThickness = 10;  ///< AvaFrame's forestVMax, forestThMax
  static constexpr double kMinSpeed = 6, kMinThickness = 0.6;  ///< forestVMin, forestThMin
  static constexpr double kDetrainment = 5; ///< AvaFrame's detK (Pa), a region's default

  explicit ResistedLaw(std::shared_ptr<const ContactLaw> base)
      : base_(std::move(base)), index_(base_->parameterNames().size()) {}

  const char* name() const override { return base_->name(); }
  bool needsThickness() const override { return true; }
  std::vector<std::string> parameterNames() const override {
    auto n = base_->parameterNames();
    n.push_back("resistance");
    n.push_back("detrainment");
    return n;
  }
  std::vector<double> parameterValues() const override {
    auto v = base_->parameterValues();
    v.push_back(0.0);
    v.push_back(0.0);
    return v;
  }
  const ContactLaw& base() const { return *base_; }
  int resistanceIndex() const { return int(index_); }
  int detrainmentIndex() const { return int(index_) + 1; }

  /// Whether the drag acts on a flow of speed u and thickness h where detK is `detK`.
  static bool drags(double u, double h, double detK) {
    if (!(detK > 0)) return true;
    return u > kMinSpeed && h > kMinThickness && u <= kMaxSpeed && h <= kMaxThickness;
  }

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
      const double detK = double(c.params[index_ + 1]);
      if (!(u > 0) || !drags(u, h, detK)) continue;
      const double k = cRes * double(dvn[i]) / (gn * h);
      const double slowed = 2 * u / (1 + std::sqrt(1 + 4 * k * u));
      c.v = vn + Real(slowed / u) * vt;
    }
  }

private:
  std::shared_ptr<const ContactLaw> base_;
  size_t index_; ///< position of `resistance` in the node's parameters (`detrainment` follows)
};

} // namespace talus
