// μ(I)'s return mapping (materials/mu_i.h) lane by lane, compiled once per Highway target: the
// implicit rate-dependent return in closed form (the one root in [0, a] of a quadratic), libm's
// exp per lane for the Cauchy pressure.
#if defined(TALUS_MATERIALS_MU_I_LANES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TALUS_MATERIALS_MU_I_LANES_INL_H_
#undef TALUS_MATERIALS_MU_I_LANES_INL_H_
#else
#define TALUS_MATERIALS_MU_I_LANES_INL_H_
#endif

#include <hwy/highway.h>

#include "materials/lanes_math-inl.h"
#include "materials/solid_lanes.h"

#include <cmath>

HWY_BEFORE_NAMESPACE();
namespace talus {
namespace HWY_NAMESPACE {
namespace lanes {

/// MuIModel::project for the lanes in `live`, in tensor form. eps: the strain, returned; strain:
/// the accumulated plastic strain. Returns the lanes whose strain changed.
HWY_INLINE M returnMuI(const SolidLaneParams& prm, V dt, Sym& eps, V& strain, M live) {
  const D d;
  const V zero = hn::Zero(d), k = hn::Set(d, prm.qScale), sq3 = hn::Set(d, std::sqrt(3.0));
  const V tr = trace(eps), third = tr / hn::Set(d, 3.0);
  const Sym dev = plusIdentity(eps, hn::Neg(third));
  const V a = hn::Sqrt(norm2(dev, hn::Set(d, 2.0)));
  const V pK = hn::Set(d, -prm.bulk) * tr; // Kirchhoff pressure
  const M tip = hn::And(live, pK <= zero);  // no confinement: the stress-free tip
  const M sliding = hn::AndNot(tip, hn::And(live, hn::Not(k * a <= sq3 * hn::Set(d, prm.muS) * pK)));
  if (!hn::AllFalse(d, sliding)) {
    // I = c x, c = sqrt(2) d / (dt sqrt(p / rho_s)), p = pK / J the Cauchy pressure.
    const V p = pK * perLane(hn::Neg(tr), sliding, [](double x) { return std::exp(x); });
    const V c = hn::Set(d, std::sqrt(2.0) * prm.grainDiameter) / (dt * hn::Sqrt(p / hn::Set(d, prm.grainDensity)));
    const V i0 = hn::Set(d, prm.i0);
    // k (a - x) (I0 + c x) = sqrt(3) pK (mu_s I0 + mu_2 c x): A x^2 + B x + C = 0, C < 0 < A.
    const V A = k * c, B = k * i0 - k * a * c + sq3 * pK * hn::Set(d, prm.mu2) * c;
    const V C = i0 * (sq3 * pK * hn::Set(d, prm.muS) - k * a);
    const V disc = hn::Sqrt(B * B - hn::Set(d, 4.0) * A * C);
    // The positive root without cancellation.
    V x = hn::IfThenElse(B >= zero, hn::Set(d, -2.0) * C / (B + disc), (disc - B) / (hn::Set(d, 2.0) * A));
    x = hn::Min(hn::Max(x, zero), a);
    eps = select(sliding, plusIdentity(scale(dev, hn::IfThenElseZero(a > zero, (a - x) / a)), third), eps);
    strain = hn::IfThenElse(sliding, strain + x, strain);
  }
  eps = select(tip, Sym{zero, zero, zero, zero, zero, zero}, eps);
  strain = hn::IfThenElse(tip, strain + a, strain);
  return hn::Or(tip, sliding);
}

} // namespace lanes
} // namespace HWY_NAMESPACE
} // namespace talus
HWY_AFTER_NAMESPACE();

#endif // include guard
