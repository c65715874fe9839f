// updateSolidLanes for every Highway target; foreach_target.h re-includes this file once per
// target. Compiled with -ffp-contract=off (materials/CMakeLists.txt): a fused multiply-add on AVX2
// but not on SSE4 would make the targets' results differ.
// Every target the compiler can emit, the portable EMU128 included, so that the tests can hold
// each against the others on one machine.
#ifndef HWY_COMPILE_ALL_ATTAINABLE
#define HWY_COMPILE_ALL_ATTAINABLE
#endif
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "materials/solid_lanes.cpp"
#include <hwy/foreach_target.h> // IWYU pragma: keep

#include <hwy/highway.h>

#include "materials/solid_lanes.h"
#include "materials/lanes_math-inl.h"
#include "materials/cam_clay_lanes-inl.h"
#include "materials/drucker_prager_lanes-inl.h"
#include "materials/mu_i_lanes-inl.h"

HWY_BEFORE_NAMESPACE();
namespace talus {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;
using namespace lanes;

namespace {

/// Row i, column j of the product of a (row by row) and b.
HWY_INLINE V product(const V* a, const V* b, int i, int j) {
  return a[3 * i] * b[j] + a[3 * i + 1] * b[3 + j] + a[3 * i + 2] * b[6 + j];
}

/// Lanes [i, i + Lanes) of io.
HWY_INLINE void updateGroup(const SolidLaneParams& prm, V dt, SolidLanes& io, size_t i) {
  const D d;
  V A[9], F[9], Ft[9];
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) {
      const V inc = dt * hn::Load(d, io.C[3 * r + c] + i);
      A[3 * r + c] = hn::Load(d, io.fbar + i) * (r == c ? hn::Set(d, 1.0) + inc : inc);
      F[3 * r + c] = hn::Load(d, io.F[3 * r + c] + i);
    }
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 3; ++c) hn::Store(Ft[3 * r + c] = product(A, F, r, c), d, io.Ftrial[3 * r + c] + i);
  const V J = Ft[0] * (Ft[4] * Ft[8] - Ft[5] * Ft[7]) - Ft[1] * (Ft[3] * Ft[8] - Ft[5] * Ft[6]) +
              Ft[2] * (Ft[3] * Ft[7] - Ft[4] * Ft[6]);
  auto row = [&](int r, int s) { return Ft[3 * r] * Ft[3 * s] + Ft[3 * r + 1] * Ft[3 * s + 1] + Ft[3 * r + 2] * Ft[3 * s + 2]; };
  const V one = hn::Set(d, 1.0);
  const Sym X{row(0, 0) - one, row(1, 1) - one, row(2, 2) - one, row(0, 1), row(0, 2), row(1, 2)};
  const M usual = hn::And(J > hn::Set(d, 1e-12), norm2(X, hn::Set(d, 2.0)) <= hn::Set(d, 0.0625));
  hn::Store(hn::IfThenElseZero(hn::Not(usual), one), d, io.scalar + i);
  if (hn::AllFalse(d, usual)) return;

  const Sym eps = halfLog(X, usual);
  Sym epsNew = eps;
  V strain = hn::Load(d, io.strain + i), extra = hn::Load(d, io.extra + i); // Cam Clay's flag
  M plastic = hn::FirstN(d, 0), handBack = hn::FirstN(d, 0);
  if (prm.kind == SolidLaneParams::Kind::DruckerPrager) plastic = hn::And(usual, returnDruckerPrager(prm, epsNew, strain));
  if (prm.kind == SolidLaneParams::Kind::MuI) plastic = returnMuI(prm, dt, epsNew, strain, usual);
  if (prm.kind == SolidLaneParams::Kind::SofteningDruckerPrager)
    plastic = returnSofteningDruckerPrager(prm, epsNew, strain, usual);
  if (prm.kind == SolidLaneParams::Kind::CamClay) {
    plastic = returnCamClay(prm, epsNew, strain, extra, usual, handBack);
    hn::Store(hn::IfThenElseZero(hn::Or(hn::Not(usual), handBack), one), d, io.scalar + i);
  }
  V Fn[9];
  for (int k = 0; k < 9; ++k) Fn[k] = Ft[k];
  if (!hn::AllFalse(d, plastic)) {
    // eps and epsNew are coaxial: exp(epsNew - eps) is the plastic correction of F.
    const Sym E = expSmall(sub(epsNew, eps), plastic);
    const V Em[9] = {E.xx, E.xy, E.xz, E.xy, E.yy, E.yz, E.xz, E.yz, E.zz};
    for (int r = 0; r < 3; ++r)
      for (int c = 0; c < 3; ++c) Fn[3 * r + c] = hn::IfThenElse(plastic, product(Em, Ft, r, c), Ft[3 * r + c]);
  }
  const Sym t = plusIdentity(scale(epsNew, hn::Set(d, 2 * prm.mu)), hn::Set(d, prm.lambda) * trace(epsNew));
  const V tv[6] = {t.xx, t.yy, t.zz, t.xy, t.xz, t.yz};
  for (int k = 0; k < 9; ++k) hn::Store(Fn[k], d, io.F[k] + i);
  for (int k = 0; k < 6; ++k) hn::Store(tv[k], d, io.tau[k] + i);
  hn::Store(strain, d, io.strain + i);
  hn::Store(extra, d, io.extra + i);
}

} // namespace

void UpdateSolidLanes(const SolidLaneParams& prm, double dt, int n, SolidLanes& io) {
  const D d;
  const size_t N = hn::Lanes(d);
  for (size_t i = 0; i < size_t(n); i += N) updateGroup(prm, hn::Set(d, dt), io, i);
}

} // namespace HWY_NAMESPACE
} // namespace talus
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace talus {
HWY_EXPORT(UpdateSolidLanes);

void updateSolidLanes(const SolidLaneParams& params, double dt, int n, SolidLanes& io) {
  HWY_DYNAMIC_DISPATCH(UpdateSolidLanes)(params, dt, n, io);
}
} // namespace talus
#endif
