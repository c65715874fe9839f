// gatherRows and scatterRows for every Highway target; foreach_target.h re-includes this file once
// per target. Compiled with -ffp-contract=off (engine/CMakeLists.txt).
#ifndef HWY_COMPILE_ALL_ATTAINABLE
#define HWY_COMPILE_ALL_ATTAINABLE // every target, so that the tests can hold each against the others
#endif
#undef HWY_TARGET_INCLUDE
#define HWY_TARGET_INCLUDE "engine/stencil_lanes.cpp"
#include <hwy/foreach_target.h> // IWYU pragma: keep

#include <hwy/highway.h>

#include "engine/padded_block.h"
#include "engine/stencil_lanes.h"

HWY_BEFORE_NAMESPACE();
namespace talus {
namespace HWY_NAMESPACE {
namespace hn = hwy::HWY_NAMESPACE;

namespace {

using DF = hn::ScalableTag<float>;
using VF = hn::Vec<DF>;
constexpr size_t kN = hn::MaxLanes(DF());
constexpr size_t kRow = 12;                   // 3 nodes of 4 floats
constexpr size_t kGroups = (kRow + kN - 1) / kN; // vectors per row: 1 (AVX-512), 2 (AVX2), 3 (SSE4), 12 (scalar)

/// The lanes of vector g that lie inside the row (all but the last vector's tail on AVX2/AVX-512).
HWY_INLINE hn::Mask<DF> inRow(size_t g) { return hn::FirstN(DF(), kRow - g * kN); }

/// The 4-float record `r` in every node's place of vector g (the record repeated along the row).
HWY_INLINE VF record(const float* r, size_t g) {
  if constexpr (kN >= 4) return hn::LoadDup128(DF(), r);
  else return hn::Load(DF(), r + (g * kN) % 4);
}

/// The w_k of each lane: w_0 four times, w_1 four times, w_2 four times, then zeros.
HWY_INLINE void nodeWeights(const float w[3], VF* W) {
  alignas(64) float lanes[16] = {w[0], w[0], w[0], w[0], w[1], w[1], w[1], w[1], w[2], w[2], w[2], w[2], 0, 0, 0, 0};
  for (size_t g = 0; g < kGroups; ++g) W[g] = hn::Load(DF(), lanes + g * kN);
}

} // namespace

void GatherRows(const float* nodes, const StencilRows& s, int n, GatheredRows& out) {
  const DF d;
  for (int p = 0; p < n; ++p) {
    VF W[kGroups], rowSum[3][kGroups], colSum[3][kGroups];
    nodeWeights(s.w[p][2], W);
    for (int i = 0; i < 3; ++i)
      for (size_t g = 0; g < kGroups; ++g) rowSum[i][g] = colSum[i][g] = hn::Zero(d);
    for (int i = 0; i < 3; ++i)
      for (int j = 0; j < 3; ++j) {
        const VF wij = hn::Set(d, s.w[p][0][i] * s.w[p][1][j]);
        const float* row = nodes + 4 * size_t(s.first[p] + padIndex(i, j, 0));
        for (size_t g = 0; g < kGroups; ++g) {
          const VF v = (wij * W[g]) * hn::MaskedLoad(inRow(g), d, row + g * kN);
          rowSum[i][g] = rowSum[i][g] + v;
          colSum[j][g] = colSum[j][g] + v;
        }
      }
    const VF two = hn::Set(d, 2.0f);
    for (size_t g = 0; g < kGroups; ++g) {
      hn::Store(rowSum[0][g] + rowSum[1][g] + rowSum[2][g], d, out.all[p] + g * kN);
      hn::Store(rowSum[1][g] + two * rowSum[2][g], d, out.alongI[p] + g * kN);
      hn::Store(colSum[1][g] + two * colSum[2][g], d, out.alongJ[p] + g * kN);
    }
  }
}

void ScatterRows(float* buf, const StencilRows& s, const ScatteredRows& q, int n) {
  const DF d;
  alignas(64) static constexpr float kNode[16] = {0, 0, 0, 0, 1, 1, 1, 1, 2, 2, 2, 2, 3, 3, 3, 3};
  for (int p = 0; p < n; ++p) {
    VF W[kGroups], q0[kGroups], a0[kGroups], a1[kGroups], qi[kGroups], ka2[kGroups];
    nodeWeights(s.w[p][2], W);
    for (size_t g = 0; g < kGroups; ++g) {
      q0[g] = record(q.q0[p], g);
      a0[g] = record(q.a0[p], g);
      a1[g] = record(q.a1[p], g);
      ka2[g] = hn::Load(d, kNode + g * kN) * record(q.a2[p], g); // 0, a2, 2 a2: exact
    }
    for (int i = 0; i < 3; ++i) {
      for (size_t g = 0; g < kGroups; ++g) qi[g] = q0[g] + hn::Set(d, float(i)) * a0[g];
      for (int j = 0; j < 3; ++j) {
        const VF wij = hn::Set(d, s.w[p][0][i] * s.w[p][1][j]);
        float* row = buf + 4 * size_t(s.first[p] + padIndex(i, j, 0));
        for (size_t g = 0; g < kGroups; ++g) {
          const VF qij = qi[g] + hn::Set(d, float(j)) * a1[g];
          const auto m = inRow(g);
          const VF sum = hn::MaskedLoad(m, d, row + g * kN) + (wij * W[g]) * (qij + ka2[g]);
          hn::BlendedStore(sum, m, d, row + g * kN);
        }
      }
    }
  }
}

const char* TargetName() { return hwy::TargetName(HWY_TARGET); }

} // namespace HWY_NAMESPACE
} // namespace talus
HWY_AFTER_NAMESPACE();

#if HWY_ONCE
namespace talus {
HWY_EXPORT(GatherRows);
HWY_EXPORT(ScatterRows);
HWY_EXPORT(TargetName);

void gatherRows(const float* nodes, const StencilRows& s, int n, GatheredRows& out) {
  HWY_DYNAMIC_DISPATCH(GatherRows)(nodes, s, n, out);
}
void scatterRows(float* buf, const StencilRows& s, const ScatteredRows& q, int n) {
  HWY_DYNAMIC_DISPATCH(ScatterRows)(buf, s, q, n);
}
const char* simdTargetName() { return HWY_DYNAMIC_DISPATCH(TargetName)(); }
std::vector<int64_t> simdTargets() { return hwy::SupportedAndGeneratedTargets(); }
void useSimdTarget(int64_t target) { hwy::SetSupportedTargetsForTest(target); }
} // namespace talus
#endif
