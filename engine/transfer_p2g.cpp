#include "engine/transfer_p2g.h"

#include "engine/bspline.h"
#include "engine/halo_exchange.h"
#include "engine/stencil_lanes.h"

#include <algorithm>
#include <cstring>

#include <tbb/parallel_for.h>

namespace talus {

namespace {

/// Where AFLIP's stress-free momentum goes: three float channels at `channel` of `buf`, stride `stride`.
struct MomentumOut {
  float* buf;
  int channel, stride;
};

/// Where factor * mass goes (thickness volume, per-material masses): `count` (channel, factor)
/// pairs, into float channels of `buf` with stride `stride`.
struct MassOut {
  float* buf;
  int stride;
  const std::pair<int, float>* to;
  size_t count;
};

/// AFLIP's stress-free momentum m (v + C (x_i - x_p)) and the mass channels of particle p (stencil
/// s, first padded node l) into their buffers.
template <bool kMomentum, bool kMass>
void scatterExtras(const ParticleSet& P, size_t p, const QuadraticStencil& s, const int l[3], Real dx, MomentumOut out,
                   MassOut mo) {
  const Real m = P.mass[p];
  const size_t stride = size_t(out.stride);
  Mat3 Md; // the momentum's affine matrix without the stress term
  Vec3 r0;
  if constexpr (kMomentum) {
    Md = (m * dx) * P.C[p];
    r0 = m * P.v[p] - Md * Vec3(s.f[0], s.f[1], s.f[2]);
  }
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j) {
      const Real wij = s.w[0][i] * s.w[1][j];
      const int pad = padIndex(l[0] + i, l[1] + j, l[2]);
      if constexpr (kMomentum) {
        const Vec3 rij = r0 + Real(i) * Md.col(0) + Real(j) * Md.col(1);
        float* node = out.buf + size_t(pad) * stride + size_t(out.channel);
        for (int k = 0; k < 3; ++k, node += stride) {
          const Vec3 r = (wij * s.w[2][k]) * (rij + Real(k) * Md.col(2));
          node[0] += float(r[0]);
          node[1] += float(r[1]);
          node[2] += float(r[2]);
        }
      }
      if constexpr (kMass) {
        float* node = mo.buf + size_t(pad) * size_t(mo.stride);
        for (int k = 0; k < 3; ++k, node += mo.stride) {
          const float w = float(wij * s.w[2][k]) * float(m);
          for (size_t t = 0; t < mo.count; ++t) node[mo.to[t].first] += w * mo.to[t].second;
        }
      }
    }
}

/// Particle p's APIC record: node (i, j, k) of its stencil receives
/// (w_i w_j) w_k (((q0 + i a0) + j a1) + k a2), a's (0, the affine momentum matrix's columns times dx).
struct AffineMomentum {
  Vec4 q0, a0, a1, a2;
  AffineMomentum(const ParticleSet& P, size_t p, const QuadraticStencil& s, Real stressScale, Real dx) {
    const Real m = P.mass[p];
    const Mat3 Ad = dx * (m * (P.C[p] - stressScale * P.tau[p].matrix())); // the affine momentum matrix
    // Momentum carried to node (i,j,k): m v + A (x_i - x_p) = q0 + i Ad0 + j Ad1 + k Ad2.
    q0 << m, m * P.v[p] - Ad * Vec3(s.f[0], s.f[1], s.f[2]);
    a0 << 0, Ad.col(0);
    a1 << 0, Ad.col(1);
    a2 << 0, Ad.col(2);
  }
};

/// Scatter particles [begin, end) of one group into the padded block buffer, sharing the stencil
/// and weights with, if kMomentum, the stress-free momentum AFLIP needs and, if kMass, the mass
/// channels. The momentum rows run in SIMD lanes, 16 particles per call (engine/stencil_lanes.h),
/// each added in particle order as the scalar loop of the double-precision build does.
template <bool kMomentum, bool kMass>
void scatterRange(const ParticleSet& P, size_t begin, size_t end, Real volumePerMass, Real dt, Real dx,
                  const int origin[3], Vec4* buf, MomentumOut out, MassOut mo) {
  const Real invDx = Real(1) / dx;
  const Real stressScale = dt * volumePerMass * Real(4) * invDx * invDx; // dt V0 D^-1 per unit mass
#ifndef TALUS_DOUBLE
  StencilRows rows;
  ScatteredRows q{};
#endif
  for (size_t first = begin; first < end; first += kStencilLanes) {
    const int n = int(std::min<size_t>(kStencilLanes, end - first));
    for (int c = 0; c < n; ++c) {
      const size_t p = first + size_t(c);
      const QuadraticStencil s(P.x[p] * invDx);
      const int l[3] = {s.base[0] - origin[0], s.base[1] - origin[1], s.base[2] - origin[2]};
      const AffineMomentum am(P, p, s, stressScale, dx);
#ifdef TALUS_DOUBLE
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const Vec4 qij = (am.q0 + Real(i) * am.a0) + Real(j) * am.a1;
          const Real wij = s.w[0][i] * s.w[1][j];
          Vec4* row = buf + padIndex(l[0] + i, l[1] + j, l[2]);
          row[0] += (wij * s.w[2][0]) * qij;
          row[1] += (wij * s.w[2][1]) * (qij + am.a2);
          row[2] += (wij * s.w[2][2]) * (qij + Real(2) * am.a2);
        }
#else
      rows.first[c] = padIndex(l[0], l[1], l[2]);
      std::copy_n(&s.w[0][0], 9, &rows.w[c][0][0]);
      std::copy_n(am.q0.data(), 4, q.q0[c]);
      std::copy_n(am.a0.data(), 4, q.a0[c]);
      std::copy_n(am.a1.data(), 4, q.a1[c]);
      std::copy_n(am.a2.data(), 4, q.a2[c]);
#endif
      if constexpr (kMomentum || kMass) scatterExtras<kMomentum, kMass>(P, p, s, l, dx, out, mo);
    }
#ifndef TALUS_DOUBLE
    scatterRows(buf[0].data(), rows, q, n);
#endif
  }
}

/// Add the padded buffer of block b (the part inside `box`) into b and its 7 upper neighbours.
void flush(const Vec4* buf, SparseGrid& grid, uint32_t b, const PadBox& box) {
  const auto& up = grid.topology.upper(b);
  forEachPaddedRow(box, [&](int d, int pad, int node, int n) {
    Vec4* out = grid.block(uint32_t(up[d])) + node;
    for (int k = 0; k < n; ++k) out[k] += buf[pad + k];
  });
}

} // namespace

PadBox reachedNodes(const std::vector<MaterialGroup*>& groups, const SparseGrid& grid, uint32_t b) {
  const Real invDx = Real(1) / grid.dx;
  const BlockCoord& bc = grid.topology.coord(b);
  const int origin[3] = {bc.x * kBlockDim, bc.y * kBlockDim, bc.z * kBlockDim};
  // A block with more particles than padded nodes almost always reaches them all, and the pass
  // below would cost more than it saves (measured: -5 % on the dense lab box).
  size_t n = 0;
  for (const MaterialGroup* g : groups) n += g->blockStart[b + 1] - g->blockStart[b];
  if (n > size_t(kPadNodes)) return PadBox{};
  PadBox box{{kPad, kPad, kPad}, {-1, -1, -1}};
  for (const MaterialGroup* g : groups)
    for (size_t p = g->blockStart[b]; p < g->blockStart[b + 1]; ++p) {
      const Vec3 xs = g->particles.x[p] * invDx; // as QuadraticStencil's base
      for (int d = 0; d < 3; ++d) {
        const int l = floorToInt(xs[d] - Real(0.5)) - origin[d];
        box.lo[d] = std::min(box.lo[d], l);
        box.hi[d] = std::max(box.hi[d], l + 2);
      }
    }
  return box;
}

void scatterBlock(const std::vector<MaterialGroup*>& groups, const SparseGrid& grid, uint32_t b, Real dt,
                  Vec4* buf, float* extra, const PadBox& box) {
  const int C = grid.channels.count;
  forEachPaddedRow(box, [&](int, int pad, int, int n) {
    std::fill(buf + pad, buf + pad + n, Vec4::Zero());
    if (C > 0) std::fill(extra + size_t(pad) * size_t(C), extra + size_t(pad + n) * size_t(C), 0.f);
  });
  const BlockCoord& bc = grid.topology.coord(b);
  const int origin[3] = {bc.x * kBlockDim, bc.y * kBlockDim, bc.z * kBlockDim};
  for (size_t gi = 0; gi < groups.size(); ++gi) {
    const MaterialGroup& g = *groups[gi];
    const size_t begin = g.blockStart[b], end = g.blockStart[b + 1];
    if (begin == end) continue;
    const Real volumePerMass = Real(1.0 / g.density());
    const MomentumOut mom{extra, grid.channels.momentum, C};
    const bool momentum = grid.channels.momentum >= 0, mass = C > 0 && !grid.channels.scatterOf[gi].empty();
    const MassOut mo{extra, C, mass ? grid.channels.scatterOf[gi].data() : nullptr, mass ? grid.channels.scatterOf[gi].size() : 0};
    const ParticleSet& P = g.particles;
    if (momentum && mass) scatterRange<true, true>(P, begin, end, volumePerMass, dt, grid.dx, origin, buf, mom, mo);
    else if (momentum) scatterRange<true, false>(P, begin, end, volumePerMass, dt, grid.dx, origin, buf, mom, mo);
    else if (mass) scatterRange<false, true>(P, begin, end, volumePerMass, dt, grid.dx, origin, buf, mom, mo);
    else scatterRange<false, false>(P, begin, end, volumePerMass, dt, grid.dx, origin, buf, mom, mo);
  }
}

namespace {

void flushExtra(const float* extra, SparseGrid& grid, uint32_t b, const PadBox& box) {
  const int C = grid.channels.count;
  const auto& up = grid.topology.upper(b);
  forEachPaddedRow(box, [&](int d, int pad, int node, int n) {
    float* out = grid.blockExtra(uint32_t(up[d])) + size_t(node) * size_t(C);
    const float* in = extra + size_t(pad) * size_t(C);
    for (int k = 0; k < n * C; ++k) out[k] += in[k];
  });
}

/// Adds rows another rank scattered (part d of its block's padded buffer) into block `target`.
void flushRemote(const RemoteRows& rows, SparseGrid& grid) {
  const int C = grid.channels.count;
  const char* nodes = rows.nodes;
  const char* extra = rows.extra;
  Vec4* block = grid.block(uint32_t(rows.target));
  float* blockExtra = C > 0 ? grid.blockExtra(uint32_t(rows.target)) : nullptr;
  forEachPaddedRow(rows.box, [&](int d, int, int node, int n) {
    if (d != rows.d) return;
    for (int k = 0; k < n; ++k, nodes += sizeof(Vec4)) {
      Vec4 v;
      std::memcpy(v.data(), nodes, sizeof(Vec4));
      block[node + k] += v;
    }
    for (int k = 0; k < n * C; ++k, extra += sizeof(float)) {
      float v;
      std::memcpy(&v, extra, sizeof(float));
      blockExtra[size_t(node) * size_t(C) + size_t(k)] += v;
    }
  });
}

} // namespace

void particlesToGrid(const std::vector<MaterialGroup*>& groups, SparseGrid& grid, Real dt, const HaloExchange* halo) {
  const int C = grid.channels.count;
  for (int colour = 0; colour < 8; ++colour) {
    const auto& local = grid.colours[size_t(colour)];
    static const std::vector<RemoteRows> kNone;
    const auto& remote = halo ? halo->remote(colour) : kNone;
    // Blocks of one colour, local or another rank's, never reach the same node: one parallel pass.
    tbb::parallel_for(tbb::blocked_range<size_t>(0, local.size() + remote.size(), 1), [&](const auto& r) {
      std::vector<Vec4> buf;
      std::vector<float> extra;
      for (size_t c = r.begin(); c != r.end(); ++c) {
        if (c >= local.size()) {
          flushRemote(remote[c - local.size()], grid);
          continue;
        }
        const uint32_t b = local[c];
        if (const Vec4* ahead = halo ? halo->stored(b) : nullptr) {
          flush(ahead, grid, b, PadBox{});
          if (C > 0) flushExtra(halo->storedExtra(b), grid, b, PadBox{});
          continue;
        }
        buf.resize(kPadNodes);
        extra.resize(size_t(kPadNodes) * size_t(std::max(C, 0)));
        const PadBox box = reachedNodes(groups, grid, b);
        scatterBlock(groups, grid, b, dt, buf.data(), extra.data(), box);
        flush(buf.data(), grid, b, box);
        if (C > 0) flushExtra(extra.data(), grid, b, box);
      }
    });
  }
}

} // namespace talus
