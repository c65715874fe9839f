// Grid-to-particle gather (APIC/MLS-MPM), shared by every material group.
#pragma once

#include "engine/bspline.h"
#include "engine/material_group.h"

#include <algorithm>
#include <array>
#include <cmath>

namespace talus {

/// The interpolated (0, v) of padded nodes `at` (the stencil's first node) under stencil s.
inline Vec3 gatherOld(const Vec4* at, const QuadraticStencil& s) {
  Vec4 v = Vec4::Zero();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const Vec4* row = at + padIndex(i, j, 0);
      v += (s.w[0][i] * s.w[1][j]) * (s.w[2][0] * row[0] + s.w[2][1] * row[1] + s.w[2][2] * row[2]);
    }
  return v.tail<3>();
}

/// The grid velocity and its gradient (APIC's C) at a particle with stencil s, whose first node is
/// padded node (l0, l1, l2) of `nodes`.
inline void gatherVelocity(const Vec4* nodes, const QuadraticStencil& s, int l0, int l1, int l2, Real invDx,
                           Vec3& vel, Mat3& C) {
  const Real cScale = Real(4) * invDx; // D^-1 = 4/dx^2, times dx from the stencil offsets
  // Node records are (mass, vx, vy, vz); the first lane accumulates junk and is ignored.
  Vec4 v = Vec4::Zero(), bi = Vec4::Zero(), bj = Vec4::Zero(), bk = Vec4::Zero();
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const Real wij = s.w[0][i] * s.w[1][j];
      const Vec4* row = nodes + padIndex(l0 + i, l1 + j, l2);
      const Vec4 w0 = (wij * s.w[2][0]) * row[0];
      const Vec4 w1 = (wij * s.w[2][1]) * row[1];
      const Vec4 w2 = (wij * s.w[2][2]) * row[2];
      const Vec4 sum = w0 + w1 + w2;
      v += sum;
      bi += Real(i) * sum;
      bj += Real(j) * sum;
      bk += w1 + Real(2) * w2;
    }
  vel = v.tail<3>();
  C.col(0) = cScale * (bi.tail<3>() - s.f[0] * vel);
  C.col(1) = cScale * (bj.tail<3>() - s.f[1] * vel);
  C.col(2) = cScale * (bk.tail<3>() - s.f[2] * vel);
}

/// Particles a group's update sees at once: the SIMD kernels' lane groups fit in it.
constexpr int kGatherChunk = 16;

/// The grid velocity and its gradient (APIC's C) at n <= kGatherChunk particles with stencils
/// s[0, n), from the padded nodes of the block whose first node is `origin`. The stencil rows run
/// in SIMD lanes (engine/stencil_lanes.h): the same bits on every target, within float rounding
/// of gatherVelocity (which sums in another order and serves the double-precision build).
void gatherChunkVelocities(const Vec4* nodes, const int origin[3], const QuadraticStencil* s, int n, Real invDx,
                           Vec3* vel, Mat3* C);

/// The interpolated scalar of padded nodes `at` (the stencil's first node) under stencil s.
inline Real gatherScalar(const Real* at, const QuadraticStencil& s) {
  Real v = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const Real* row = at + padIndex(i, j, 0);
      v += (s.w[0][i] * s.w[1][j]) * (s.w[2][0] * row[0] + s.w[2][1] * row[1] + s.w[2][2] * row[2]);
    }
  return v;
}

/// det(I + A) - 1, without the cancellation of forming det(I + A) in float first.
inline double volumeChangeMinusOne(const Mat3d& A) {
  const double t = A.trace();
  return t + 0.5 * (t * t - (A * A).trace()) + A.determinant();
}

/// F-bar's factor ((1 + mean) / ΔJ)^(1/3) on a particle's deformation increment I + dt C, with ΔJ
/// its own volume change and `mean` the mass-weighted mean of ΔJ - 1 around it (1 when degenerate).
inline double fbarScale(const Mat3& C, Real dt, double mean) {
  const double own = volumeChangeMinusOne(double(dt) * C.cast<double>());
  if (!(own > -1) || !(mean > -1)) return 1;
  return std::exp((std::log1p(mean) - std::log1p(own)) / 3);
}

/// What the gather hands a group's update for up to kGatherChunk consecutive particles: their
/// range and F-bar's scale of each one's deformation increment (1 when that is off). Their v and
/// C are already in the particle set.
struct GatheredChunk {
  size_t first = 0;
  int count = 0;
  double fbar[kGatherChunk];
  double meanJ[kGatherChunk]; ///< G2PBlock::meanJ at each particle (0 when that is null)
};

/// Gathers v and C for particles [begin, end) chunk by chunk, lets `update(chunk)` advance the
/// chunk's material state (deformation, return mapping, Kirchhoff stress), then advects x with
/// the new velocity. A particle's result does not depend on the chunking.
template <class UpdateChunkFn>
inline void gatherParticleChunks(const G2PBlock& blk, ParticleSet& P, size_t begin, size_t end,
                                 G2PStats& stats, UpdateChunkFn&& update) {
  const Real invDx = blk.invDx, dt = blk.dt;
  Real maxSpeed2 = stats.maxSpeed * stats.maxSpeed;
  GatheredChunk chunk;
  QuadraticStencil st[kGatherChunk];
  Vec3 vel[kGatherChunk];
  Mat3 C[kGatherChunk];
  for (size_t q = begin; q < end; q += kGatherChunk) {
    chunk.first = q;
    chunk.count = int(std::min<size_t>(kGatherChunk, end - q));
    for (int k = 0; k < chunk.count; ++k) st[k] = QuadraticStencil(P.x[q + size_t(k)] * invDx);
    gatherChunkVelocities(blk.nodes, blk.origin, st, chunk.count, invDx, vel, C);
    for (int k = 0; k < chunk.count; ++k) {
      const size_t p = q + size_t(k);
      const QuadraticStencil& s = st[k];
      const int pad = padIndex(s.base[0] - blk.origin[0], s.base[1] - blk.origin[1], s.base[2] - blk.origin[2]);
      if (blk.old) P.v[p] = vel[k] + blk.flip * (P.v[p] - gatherOld(blk.old + pad, s));
      else P.v[p] = vel[k];
      P.C[p] = C[k];
      chunk.fbar[k] = blk.meanVolumeChange ? fbarScale(C[k], dt, double(gatherScalar(blk.meanVolumeChange + pad, s))) : 1.0;
      chunk.meanJ[k] = blk.meanJ ? double(gatherScalar(blk.meanJ + pad, s)) : 0.0;
    }
    update(static_cast<const GatheredChunk&>(chunk));
    for (int k = 0; k < chunk.count; ++k) {
      const size_t p = q + size_t(k);
      P.x[p] += dt * vel[k]; // with the PIC velocity also under AFLIP (Fei et al. 2021)
      // x - x is 0 for finite x and NaN otherwise: one test catches a bad stress in this step.
      const Sym3& t = P.tau[p];
      const Real finite = (t.xx - t.xx) + (t.yy - t.yy) + (t.zz - t.zz) + (t.xy - t.xy) + (t.xz - t.xz) + (t.yz - t.yz);
      const Real s2 = std::max(vel[k].squaredNorm(), P.v[p].squaredNorm());
      const bool badSpeed = !std::isfinite(s2);
      if (!badSpeed && s2 > maxSpeed2) maxSpeed2 = s2;
      if (badSpeed || !(finite == Real(0))) ++stats.nonFinite;
    }
  }
  stats.maxSpeed = std::sqrt(maxSpeed2);
}

/// gatherParticleChunks with a per-particle update: `update(i, C, s)` for particle i, its velocity
/// gradient C and F-bar's scale s.
template <class UpdateFn>
inline void gatherParticles(const G2PBlock& blk, ParticleSet& P, size_t begin, size_t end,
                            G2PStats& stats, UpdateFn&& update) {
  gatherParticleChunks(blk, P, begin, end, stats, [&](const GatheredChunk& c) {
    for (int k = 0; k < c.count; ++k) update(c.first + size_t(k), P.C[c.first + size_t(k)], c.fbar[k]);
  });
}

} // namespace talus

namespace talus {
struct SparseGrid;
/// The nodes of a block's padded neighbourhood (`up`: it and its 7 upper neighbours) inside `box`,
/// in padIndex order.
void copyPaddedNodes(const SparseGrid& grid, const std::array<int32_t, 8>& up, Vec4* out, const PadBox& box = PadBox{});
/// Runs G2P (and through each group, deformation update, return mapping and stress) for all
/// owning blocks in parallel. Blocks only read the grid, so no colouring is needed.
G2PStats gridToParticles(const std::vector<MaterialGroup*>& groups, const SparseGrid& grid, Real dt, Real flip = 0);
} // namespace talus
