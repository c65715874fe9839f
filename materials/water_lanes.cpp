// updateWaterLanes for every Highway target; foreach_target.h re-includes this file once per
// target. Compiled with -ffp-contract=off (materials/CMakeLists.txt), as the solids' kernel.
#ifndef HWY_COMPILE_ALL_ATTAINABLE
#define HWY_COMPILE_ALL_ATTAINABLE // every target, so that the tests can hold each against the others
#endif
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "materials/water_lanes.cpp"
#include <hwy/foreach_target.h> // IWYU pragma: keep

#include <hwy/highway.h>

#include "materials/lanes_math-inl.h"
#include "materials/water_lanes.h"

#include <cmath>

HWY_BEFORE_NAMESPACE();
namespace talus {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
using namespace lanes;

namespace {

/// Lanes [i, i + Lanes) of io: J <- J det(I + dt C), p = B (J^-k - 1), tau = J (-p I + 2 eta dev D).
HWY_INLINE void updateGroup(const TaitWaterModel& m, double dMax, V dt, WaterLanes& io, size_t i) {
  const D d;
  V A[9];
  for (int k = 0; k < 9; ++k) A[k] = dt * hn::Load(d, io.C[k] + i);
  // det(I + A) - 1 by its invariants, exact and free of cancellation for small A.
  const V tr = A[0] + A[4] + A[8];
  V trSquare = hn::Zero(d);
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) trSquare = trSquare + A[3 * r + c] * A[3 * c + r];
  const V det = A[0] * (A[4] * A[8] - A[5] * A[7]) - A[1] * (A[3] * A[8] - A[5] * A[6]) +
                A[2] * (A[3] * A[7] - A[4] * A[6]);
  const V delta = tr + hn::Set(d, 0.5) * (tr * tr - trSquare) + det;
  const V dJ = hn::Load(d, io.dJ + i);
  const V dNew = hn::Min(dJ + delta + dJ * delta, hn::Set(d, dMax));
  const double bulk = m.bulk, k = m.exponent;
  const V p = perLane(dNew, hn::FirstN(d, hn::Lanes(d)), [bulk, k](double x) { return bulk * std::expm1(-k * std::log1p(x)); });
  const V J = hn::Set(d, 1.0) + dNew;
  V t[6];
  const V diag = hn::Neg(J) * p, zero = hn::Zero(d);
  t[0] = t[1] = t[2] = diag;
  t[3] = t[4] = t[5] = zero;
  if (m.viscosity > 0) {
    const V half = hn::Set(d, 0.5), s = J * hn::Set(d, 2 * m.viscosity);
    const V Dm[6] = {hn::Load(d, io.C[0] + i), hn::Load(d, io.C[4] + i), hn::Load(d, io.C[8] + i),
                     half * (hn::Load(d, io.C[1] + i) + hn::Load(d, io.C[3] + i)),
                     half * (hn::Load(d, io.C[2] + i) + hn::Load(d, io.C[6] + i)),
                     half * (hn::Load(d, io.C[5] + i) + hn::Load(d, io.C[7] + i))};
    const V third = (Dm[0] + Dm[1] + Dm[2]) / hn::Set(d, 3.0);
    for (int c = 0; c < 3; ++c) t[c] = t[c] + s * (Dm[c] - third);
    for (int c = 3; c < 6; ++c) t[c] = s * Dm[c];
  }
  hn::Store(dNew, d, io.dJ + i);
  for (int c = 0; c < 6; ++c) hn::Store(t[c], d, io.tau[c] + i);
}

} // namespace

void UpdateWaterLanes(const TaitWaterModel& m, double dt, int n, WaterLanes& io) {
  const D d;
  // maxJ() is a pow; without tension (the default) it is exactly 1.
  const double dMax = m.maxTension > 0 ? m.maxJ() - 1 : 0.0;
  for (size_t i = 0; i < size_t(n); i += hn::Lanes(d)) updateGroup(m, dMax, hn::Set(d, dt), io, i);
}

} // namespace HWY_NAMESPACE
} // namespace talus
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace talus {
HWY_EXPORT(UpdateWaterLanes);

void updateWaterLanes(const TaitWaterModel& model, double dt, int n, WaterLanes& io) {
  HWY_DYNAMIC_DISPATCH(UpdateWaterLanes)(model, dt, n, io);
}
} // namespace talus
#endif
