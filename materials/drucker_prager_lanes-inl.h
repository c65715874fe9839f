// Drucker–Prager's return mapping (materials/drucker_prager.h) lane by lane, compiled once per
// Highway target: at constant strength in closed form, and with exponential softening by the
// model's safeguarded Newton on the updated strength (libm's exp, sin and cos per lane).
#if defined(TALUS_MATERIALS_DRUCKER_PRAGER_LANES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TALUS_MATERIALS_DRUCKER_PRAGER_LANES_INL_H_
#undef TALUS_MATERIALS_DRUCKER_PRAGER_LANES_INL_H_
#else
#define TALUS_MATERIALS_DRUCKER_PRAGER_LANES_INL_H_
#endif

#include <hwy/highway.h>

#include "materials/lanes_math-inl.h"
#include "materials/solid_lanes.h"

#include <cmath>

HWY_BEFORE_NAMESPACE();
namespace talus {
namespace HWY_NAMESPACE {
namespace lanes {

/// The return of Drucker–Prager at constant strength in tensor form (the model's project on the
/// principal strains, which depends on them only through the trace and the deviator's norm).
/// Returns the plastic lanes; eps becomes the returned strain, `strain` the accumulated one.
HWY_INLINE M returnDruckerPrager(const SolidLaneParams& prm, Sym& eps, V& strain) {
  const D d;
  const V tr = trace(eps), third = tr / hn::Set(d, 3.0);
  const Sym dev = plusIdentity(eps, hn::Neg(third));
  const V a = hn::Sqrt(norm2(dev, hn::Set(d, 2.0)));
  const V pc = hn::Set(d, -prm.bulk) * tr + hn::Set(d, prm.cohesion); // p + c
  const M plastic = hn::Not(hn::Set(d, prm.qScale) * a - hn::Set(d, prm.gamma) * pc <= hn::Zero(d));
  if (hn::AllFalse(d, plastic)) return plastic;
  const M tip = hn::And(plastic, pc <= hn::Zero(d));
  const V aNew = hn::Set(d, prm.gamma) * pc / hn::Set(d, prm.qScale);
  const Sym cone = plusIdentity(scale(dev, aNew / a), third);
  const V tipStrain = hn::Set(d, prm.cohesion / (3 * prm.bulk));
  const V z = hn::Zero(d);
  const Sym atTip{tipStrain, tipStrain, tipStrain, z, z, z};
  eps = select(plastic, select(tip, atTip, cone), eps);
  strain = hn::IfThenElse(plastic, hn::IfThenElse(tip, strain + a, strain + a - aNew), strain);
  return plastic;
}

/// The softened strength at accumulated strain e: the cone's gamma, the cohesion and their
/// derivatives in e (DruckerPragerModel::gammaOf, gammaSlope, frictionAngle, cohesion).
struct Strength {
  V gamma, dGamma, cohesion, dCohesion;
};

/// exp(-chi e) per lane: the softened share of the strength that is left.
HWY_INLINE V decayAt(const SolidLaneParams& prm, V e, M live) {
  const double chi = prm.softening;
  return perLane(e, live, [chi](double x) { return std::exp(-chi * x); });
}

HWY_INLINE Strength strengthAt(const SolidLaneParams& prm, V e, M live) {
  const D d;
  const double chi = prm.softening;
  const V decay = decayAt(prm, e, live);
  const V drop = hn::Set(d, prm.frictionAngle - prm.residualFrictionAngle);
  const V phi = hn::Set(d, prm.residualFrictionAngle) + drop * decay;
  const V s = perLane(phi, live, [](double x) { return std::sin(x); });
  const V c = perLane(phi, live, [](double x) { return std::cos(x); });
  V g, slope;
  switch (prm.cone) {
  case DruckerPragerCone::PlaneStrain:
    g = hn::Set(d, std::sqrt(3.0)) * s, slope = hn::Set(d, std::sqrt(3.0)) * c;
    break;
  case DruckerPragerCone::Extension:
    g = hn::Set(d, 6.0) * s / (hn::Set(d, 3.0) + s);
    slope = hn::Set(d, 18.0) * c / ((hn::Set(d, 3.0) + s) * (hn::Set(d, 3.0) + s));
    break;
  default:
    g = hn::Set(d, 6.0) * s / (hn::Set(d, 3.0) - s);
    slope = hn::Set(d, 18.0) * c / ((hn::Set(d, 3.0) - s) * (hn::Set(d, 3.0) - s));
  }
  const V cohesion = hn::Set(d, prm.cohesion) * decay;
  return {g, slope * (hn::Set(d, -chi) * drop * decay), cohesion, hn::Set(d, -chi) * cohesion};
}

/// DruckerPragerModel::project with softening, for the lanes in `live`, in tensor form: the tip
/// when even the whole deviator's plastic strain leaves the state beyond it, else the root d in
/// [0, a] of h(d) = k (a - d) - gamma(e0 + d) (p + c(e0 + d)) by Newton safeguarded by bisection.
/// Returns the plastic lanes; eps becomes the returned strain, `strain` the accumulated one.
HWY_INLINE M returnSofteningDruckerPrager(const SolidLaneParams& prm, Sym& eps, V& strain, M live) {
  const D d;
  const V zero = hn::Zero(d), k = hn::Set(d, prm.qScale);
  const V tr = trace(eps), third = tr / hn::Set(d, 3.0);
  const Sym dev = plusIdentity(eps, hn::Neg(third));
  const V a = hn::Sqrt(norm2(dev, hn::Set(d, 2.0)));
  const V p = hn::Set(d, -prm.bulk) * tr, e0 = strain;
  const Strength s0 = strengthAt(prm, e0, live);
  const M plastic = hn::And(live, hn::Not(k * a - s0.gamma * (p + s0.cohesion) <= zero));
  if (hn::AllFalse(d, plastic)) return plastic;
  const V cFull = hn::Set(d, prm.cohesion) * decayAt(prm, e0 + a, plastic); // c(e0 + a): no sin, cos needed
  const M tip = hn::And(plastic, p + cFull <= zero);
  M active = hn::AndNot(tip, plastic);
  V lo = zero, hi = a;
  V dd = hn::Min(hn::Max(a - s0.gamma * (p + s0.cohesion) / k, zero), a); // the explicit return
  for (int it = 0; it < 60 && !hn::AllFalse(d, active); ++it) {
    const Strength st = strengthAt(prm, e0 + dd, active);
    const V f = k * (a - dd) - st.gamma * (p + st.cohesion);
    const V dh = hn::Neg(k) - st.dGamma * (p + st.cohesion) - st.gamma * st.dCohesion;
    active = hn::AndNot(hn::Abs(f) <= hn::Set(d, 1e-12) * k * a, active);
    const M above = hn::And(active, f > zero), below = hn::AndNot(f > zero, active);
    lo = hn::IfThenElse(above, dd, lo);
    hi = hn::IfThenElse(below, dd, hi);
    V next = dd - f / dh;
    next = hn::IfThenElse(hn::And(next > lo, next < hi), next, hn::Set(d, 0.5) * (lo + hi));
    active = hn::AndNot(hi - lo <= hn::Set(d, 1e-15) * a, active);
    dd = hn::IfThenElse(active, next, dd);
  }
  const V tipStrain = cFull / (hn::Set(d, 3.0) * hn::Set(d, prm.bulk));
  const Sym atTip{tipStrain, tipStrain, tipStrain, zero, zero, zero};
  const Sym onCone = plusIdentity(scale(dev, hn::IfThenElseZero(a > zero, (a - dd) / a)), third);
  eps = select(plastic, select(tip, atTip, onCone), eps);
  strain = hn::IfThenElse(plastic, hn::IfThenElse(tip, e0 + a, e0 + dd), strain);
  return plastic;
}

} // namespace lanes
} // namespace HWY_NAMESPACE
} // namespace talus
HWY_AFTER_NAMESPACE();

#endif // include guard
