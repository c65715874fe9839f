// Arithmetic of the SIMD-lane kernels (materials/solid_lanes.cpp), compiled once per Highway target:
// a symmetric 3x3 matrix per lane and the Hencky series of materials/hencky.h, lane by lane.
// Per-target include guard (Highway's convention for -inl.h files).
#if defined(TALUS_MATERIALS_LANES_MATH_INL_H_) == defined(HWY_TARGET_TOGGLE)
#ifdef TALUS_MATERIALS_LANES_MATH_INL_H_
#undef TALUS_MATERIALS_LANES_MATH_INL_H_
#else
#define TALUS_MATERIALS_LANES_MATH_INL_H_
#endif

#include <hwy/highway.h>

HWY_BEFORE_NAMESPACE();
namespace talus {
namespace HWY_NAMESPACE {
namespace lanes {
namespace hn = hwy::HWY_NAMESPACE;

using D = hn::ScalableTag<double>;
using V = hn::Vec<D>;
using M = hn::Mask<D>;

/// A symmetric 3x3 matrix per lane, with the products of detail::SymD (commuting matrices only).
struct Sym {
  V xx, yy, zz, xy, xz, yz;
};

HWY_INLINE Sym mul(const Sym& a, const Sym& b) {
  return {a.xx * b.xx + a.xy * b.xy + a.xz * b.xz, a.xy * b.xy + a.yy * b.yy + a.yz * b.yz,
          a.xz * b.xz + a.yz * b.yz + a.zz * b.zz, a.xx * b.xy + a.xy * b.yy + a.xz * b.yz,
          a.xx * b.xz + a.xy * b.yz + a.xz * b.zz, a.xy * b.xz + a.yy * b.yz + a.yz * b.zz};
}
HWY_INLINE Sym scale(const Sym& a, V s) { return {a.xx * s, a.yy * s, a.zz * s, a.xy * s, a.xz * s, a.yz * s}; }
HWY_INLINE Sym add(const Sym& a, const Sym& b) {
  return {a.xx + b.xx, a.yy + b.yy, a.zz + b.zz, a.xy + b.xy, a.xz + b.xz, a.yz + b.yz};
}
HWY_INLINE Sym sub(const Sym& a, const Sym& b) {
  return {a.xx - b.xx, a.yy - b.yy, a.zz - b.zz, a.xy - b.xy, a.xz - b.xz, a.yz - b.yz};
}
HWY_INLINE Sym plusIdentity(const Sym& a, V s) { return {a.xx + s, a.yy + s, a.zz + s, a.xy, a.xz, a.yz}; }
HWY_INLINE Sym select(M m, const Sym& a, const Sym& b) {
  return {hn::IfThenElse(m, a.xx, b.xx), hn::IfThenElse(m, a.yy, b.yy), hn::IfThenElse(m, a.zz, b.zz),
          hn::IfThenElse(m, a.xy, b.xy), hn::IfThenElse(m, a.xz, b.xz), hn::IfThenElse(m, a.yz, b.yz)};
}
HWY_INLINE V trace(const Sym& a) { return a.xx + a.yy + a.zz; }
HWY_INLINE V norm2(const Sym& a, V two) {
  return a.xx * a.xx + a.yy * a.yy + a.zz * a.zz + two * (a.xy * a.xy + a.xz * a.xz + a.yz * a.yz);
}
HWY_INLINE Sym inverse(const Sym& a) {
  const V cxx = a.yy * a.zz - a.yz * a.yz, cxy = a.xz * a.yz - a.xy * a.zz, cxz = a.xy * a.yz - a.xz * a.yy;
  const V inv = hn::Set(D(), 1.0) / (a.xx * cxx + a.xy * cxy + a.xz * cxz);
  return {cxx * inv, (a.xx * a.zz - a.xz * a.xz) * inv, (a.xx * a.yy - a.xy * a.xy) * inv, cxy * inv, cxz * inv,
          (a.xy * a.xz - a.xx * a.yz) * inv};
}

/// log(I + X) / 2 by the atanh series of detail::halfLogNearIdentity, each lane stopping at its
/// own term (lanes outside `live` are not iterated for).
HWY_INLINE Sym halfLog(const Sym& X, M live) {
  const D d;
  const Sym Y = mul(X, inverse(plusIdentity(X, hn::Set(d, 2.0))));
  const Sym Y2 = mul(Y, Y);
  const V r2 = trace(Y2);
  Sym sum = Y, term = Y;
  V rk = hn::Set(d, 1.0);
  for (int k = 3; k <= 15; k += 2) {
    rk = rk * r2;
    live = hn::AndNot(rk < hn::Set(d, 1e-24), live);
    if (hn::AllFalse(d, live)) break;
    term = mul(term, Y2);
    sum = select(live, add(sum, scale(term, hn::Set(d, 1.0 / k))), sum);
  }
  return sum;
}

/// exp(A) by the Taylor series of detail::expSmall, per lane.
HWY_INLINE Sym expSmall(const Sym& A, M live) {
  const D d;
  const V r = hn::Sqrt(norm2(A, hn::Set(d, 2.0)));
  Sym sum = plusIdentity(A, hn::Set(d, 1.0)), term = A;
  V rk = r;
  for (int k = 2; k <= 16; ++k) {
    rk = rk * (r / hn::Set(d, double(k)));
    live = hn::AndNot(rk < hn::Set(d, 1e-13), live);
    if (hn::AllFalse(d, live)) break;
    term = scale(mul(term, A), hn::Set(d, 1.0 / k));
    sum = select(live, add(sum, term), sum);
  }
  return sum;
}

/// fn (a scalar function such as libm's sinh) of the lanes in `live`, 0 in the others: the same
/// bits on every target.
template <class Fn>
HWY_INLINE V perLane(V v, M live, Fn fn) {
  const D d;
  alignas(64) double buf[8], on[8]; // the widest target holds 8 doubles
  static_assert(hn::MaxLanes(D()) <= 8, "a vector of at most 8 doubles");
  hn::Store(v, d, buf);
  hn::Store(hn::IfThenElseZero(live, hn::Set(d, 1.0)), d, on);
  for (size_t i = 0; i < hn::Lanes(d); ++i) buf[i] = on[i] != 0 ? fn(buf[i]) : 0.0;
  return hn::Load(d, buf);
}

/// std::isfinite per lane (x - x is 0 for finite x, NaN otherwise).
HWY_INLINE M isFinite(V v) { return (v - v) == hn::Zero(D()); }

} // namespace lanes
} // namespace HWY_NAMESPACE
} // namespace talus
HWY_AFTER_NAMESPACE();

#endif // include guard
