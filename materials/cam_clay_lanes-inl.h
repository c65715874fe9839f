// Cam Clay's return mapping (materials/cam_clay.h) lane by lane, compiled once per Highway target:
// the same closest point on the ellipse, the same consistent-hardening Newton, each lane iterating
// until its own test stops it (masked), the others keeping their values. A lane whose Newton does
// not converge is handed back: the caller runs the scalar update, with its bracketed solve.
#if defined(TALUS_MATERIALS_CAM_CLAY_LANES_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TALUS_MATERIALS_CAM_CLAY_LANES_INL_H_
#undef TALUS_MATERIALS_CAM_CLAY_LANES_INL_H_
#else
#define TALUS_MATERIALS_CAM_CLAY_LANES_INL_H_
#endif

#include <hwy/highway.h>

#include "materials/lanes_math-inl.h"
#include "materials/solid_lanes.h"

#include <cmath>

HWY_BEFORE_NAMESPACE();
namespace talus {
namespace HWY_NAMESPACE {
namespace lanes {

/// The ellipse's constants (the square roots computed once per group, SolidLaneParams), broadcast.
struct CamClayConstants {
  V K, xi, sK, s3mu, halfTension, halfCentre, Ms, sqrtTension, beta, tension, three;
  double bulk, xiScalar;
  explicit CamClayConstants(const SolidLaneParams& c)
      : K(hn::Set(D(), c.bulk)), xi(hn::Set(D(), c.xi)), sK(hn::Set(D(), c.sqrtBulk)),
        s3mu(hn::Set(D(), c.sqrt3mu)), halfTension(hn::Set(D(), 0.5 * (1 + c.beta))),
        halfCentre(hn::Set(D(), 0.5 * (1 - c.beta))), Ms(hn::Set(D(), c.Ms)),
        sqrtTension(hn::Set(D(), c.sqrtTension)), beta(hn::Set(D(), c.beta)),
        tension(hn::Set(D(), 1 + 2 * c.beta)), three(hn::Set(D(), 3.0)), bulk(c.bulk), xiScalar(c.xi) {}
};

/// p0 = K sinh(xi max(-eps_v, 0)) per lane (libm's sinh, as the scalar model).
HWY_INLINE V preconsolidation(const CamClayConstants& c, V ev, M live) {
  const double K = c.bulk, xi = c.xiScalar;
  return perLane(ev, live, [K, xi](double e) { return K * std::sinh(xi * std::max(-e, 0.0)); });
}

/// CamClayModel::closestOnEllipse for the lanes in `live` (x, y >= 0, outside): Newton on
/// S^(-1/2) - 1 from the lower bound or the warm start t. Other lanes keep t.
HWY_INLINE void closestOnEllipse(V x, V y, V A, V B, V& px, V& py, V& t, M live) {
  const D d;
  const V one = hn::Set(d, 1.0), zero = hn::Zero(d);
  const V a = A * x, b = B * y, A2 = A * A, B2 = B * B;
  auto eval = [&](V s, V& Dv) {
    const V ua = one / (s + A2), ub = one / (s + B2);
    const V ra = a * ua, rb = b * ub;
    Dv = ra * ra * ua + rb * rb * ub;
    return ra * ra + rb * rb;
  };
  auto step = [&](V S, V Dv) { return S * (hn::Sqrt(S) - one) / Dv; };
  const V bound = hn::Max(zero, hn::Sqrt(a * a + b * b) - hn::Max(A2, B2));
  const V guess = t;
  V s = bound;
  const M warm = hn::And(live, guess > bound);
  if (!hn::AllFalse(d, warm)) {
    V Dv;
    const V S = eval(guess, Dv);
    s = hn::IfThenElse(warm, hn::IfThenElse(S >= one, guess, hn::Max(bound, guess + step(S, Dv))), s);
  }
  M active = live;
  for (int it = 0; it < 100; ++it) {
    V Dv;
    const V S = eval(s, Dv);
    active = hn::AndNot(S - one <= hn::Set(d, 1e-15), active);
    if (hn::AllFalse(d, active)) break;
    const V ds = step(S, Dv);
    s = hn::IfThenElse(active, s + ds, s);
    active = hn::AndNot(ds <= hn::Set(d, 1e-16) * (s + A2 + B2), active);
  }
  t = hn::IfThenElse(live, s, t);
  px = A2 * x / (s + A2);
  py = B2 * y / (s + B2);
}

/// CamClayModel::projectOntoEllipse for the lanes in `live`: (p, q) on the M_s ellipse of p0 and
/// their derivatives in p0. Other lanes get garbage in p, q, dp, dq and keep t.
HWY_INLINE void projectOntoEllipse(const CamClayConstants& c, V pTr, V qTr, V p0, V& p, V& q, V& dp, V& dq,
                                   V& t, M live) {
  const D d;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
  const M strength = p0 > zero;
  const V ap = c.halfTension * p0, centre = c.halfCentre * p0;
  const V aq = c.Ms * ap / c.sqrtTension;
  const V x = (pTr - centre) / c.sK, y = qTr / c.s3mu, A = ap / c.sK, B = aq / c.s3mu;
  const M inside = (x / A) * (x / A) + (y / B) * (y / B) <= one;
  const M outside = hn::And(live, hn::AndNot(inside, strength));
  p = hn::IfThenElse(strength, pTr, zero);
  q = hn::IfThenElse(strength, qTr, zero);
  dp = zero, dq = zero;
  if (hn::AllFalse(d, outside)) return;
  V X, Y;
  closestOnEllipse(hn::Abs(x), y, A, B, X, Y, t, outside);
  const V sign = hn::IfThenElse(x < zero, hn::Set(d, -1.0), one);
  const V pO = centre + c.sK * sign * X, qO = c.s3mu * Y;
  const V nx = X / (A * A), ny = Y / (B * B), n2 = nx * nx + ny * ny;
  const V tangential = (hn::Neg(ny) * sign * pTr / c.sK + nx * y) / (n2 * (one + t / (A * A * B * B * n2)));
  p = hn::IfThenElse(outside, pO, p);
  q = hn::IfThenElse(outside, qO, q);
  dp = hn::IfThenElse(outside, (pO - c.sK * sign * hn::Neg(ny) * tangential) / p0, zero);
  dq = hn::IfThenElse(outside, (qO - c.s3mu * nx * tangential) / p0, zero);
}

/// CamClayModel::hardenNewton for the lanes in `live`: eps_v, p and q on the ellipse of the
/// updated p0. Returns the lanes that did not converge (left to the scalar bracketed solve).
HWY_INLINE M hardenNewton(const CamClayConstants& c, V pTr, V qTr, V ev0, V p00, V& ev, V& p, V& q, M live) {
  const D d;
  const V zero = hn::Zero(d), one = hn::Set(d, 1.0);
  ev = ev0;
  V p0 = p00, t = zero, pOut = zero, qOut = zero;
  M active = live, failed = hn::FirstN(d, 0);
  for (int it = 0; it < 12; ++it) {
    V dp, dq;
    projectOntoEllipse(c, pTr, qTr, p0, p, q, dp, dq, t, active);
    const V dp0 = hn::IfThenElseZero(ev < zero, hn::Neg(c.xi) * hn::Sqrt(c.K * c.K + p0 * p0));
    const V g = ev - ev0 - (p - pTr) / c.K, slopeG = one - dp * dp0 / c.K;
    const V step = hn::Neg(g) / slopeG;
    const M bad = hn::And(active, hn::Not(hn::And(slopeG > zero, isFinite(step))));
    failed = hn::Or(failed, bad);
    active = hn::AndNot(bad, active);
    ev = hn::IfThenElse(active, ev + step, ev);
    const M done = hn::And(active, hn::Abs(step) <= hn::Set(d, 1e-9) * (one + hn::Abs(ev)));
    pOut = hn::IfThenElse(done, p + dp * dp0 * step, pOut);
    qOut = hn::IfThenElse(done, q + dq * dp0 * step, qOut);
    active = hn::AndNot(done, active);
    if (hn::AllFalse(d, active)) break;
    p0 = hn::IfThenElse(active, preconsolidation(c, ev, active), p0);
  }
  p = pOut, q = qOut;
  return hn::Or(failed, active);
}

/// CamClayModel::project in tensor form. eps: the strain, returned; ev: eps_v in and out; yielded:
/// the flag (0 or 1) in and out. Returns the plastic lanes; `handBack` gets the lanes whose
/// hardening did not converge.
HWY_INLINE M returnCamClay(const SolidLaneParams& prm, Sym& eps, V& ev, V& yielded, M live, M& handBack) {
  const D d;
  const CamClayConstants c(prm);
  const V zero = hn::Zero(d);
  const V tr = trace(eps);
  const Sym dev = plusIdentity(eps, hn::Neg(tr / c.three));
  const V a = hn::Sqrt(norm2(dev, hn::Set(d, 2.0)));
  const V pTr = hn::Neg(c.K) * tr, qTr = hn::Set(d, prm.qScale) * a;
  const V ev0 = ev, p00 = preconsolidation(c, ev0, live);
  const V slope = hn::IfThenElse(yielded > zero, c.Ms, hn::Set(d, prm.M));
  const V f = qTr * qTr * c.tension + slope * slope * (pTr + c.beta * p00) * (pTr - p00);
  const M plastic = hn::And(live, hn::Not(f <= zero));
  handBack = hn::FirstN(d, 0);
  if (hn::AllFalse(d, plastic)) return plastic;
  V evNew, p, q;
  handBack = hardenNewton(c, pTr, qTr, ev0, p00, evNew, p, q, plastic);
  const M moved = hn::AndNot(handBack, plastic);
  const V s = hn::IfThenElseZero(a > zero, q / qTr);
  eps = select(moved, plusIdentity(scale(dev, s), hn::Neg(p) / (c.three * c.K)), eps);
  ev = hn::IfThenElse(moved, evNew, ev);
  yielded = hn::IfThenElse(moved, hn::Set(d, 1.0), yielded);
  return moved;
}

} // namespace lanes
} // namespace HWY_NAMESPACE
} // namespace talus
HWY_AFTER_NAMESPACE();

#endif // include guard
