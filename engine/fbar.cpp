#include "engine/fbar.h"

#include "engine/bspline.h"
#include "engine/transfer_g2p.h"

#include <algorithm>

#include <tbb/parallel_for.h>

namespace talus {

namespace {

/// m (ΔJ - 1) and m of particles [begin, end) into the padded two-channel buffer `sums`; their C
/// is gathered as G2P gathers it (gatherChunkVelocities), 16 particles at a time.
/// `state`: J - 1 per particle before the step when the group averages its J (then the sum is of
/// its J after the step, cut at 1 + stateMax as the group's own update cuts it), or null.
void scatterVolumeChange(const ParticleSet& P, const float* state, double stateMax, size_t begin, size_t end,
                         const Vec4* nodes, const int origin[3], Real dt, Real invDx, float* sums) {
  QuadraticStencil st[kGatherChunk];
  Vec3 vel[kGatherChunk];
  Mat3 C[kGatherChunk];
  for (size_t first = begin; first < end; first += kGatherChunk) {
    const int n = int(std::min<size_t>(kGatherChunk, end - first));
    for (int c = 0; c < n; ++c) st[c] = QuadraticStencil(P.x[first + size_t(c)] * invDx);
    gatherChunkVelocities(nodes, origin, st, n, invDx, vel, C);
    for (int c = 0; c < n; ++c) {
      const size_t p = first + size_t(c);
      const QuadraticStencil& s = st[c];
      const int l0 = s.base[0] - origin[0], l1 = s.base[1] - origin[1], l2 = s.base[2] - origin[2];
      double change = volumeChangeMinusOne(double(dt) * C[c].cast<double>());
      if (state) change = std::min(stateMax, change + double(state[p]) * (1 + change));
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          float* row = sums + 2 * size_t(padIndex(l0 + i, l1 + j, l2));
          for (int k = 0; k < 3; ++k) {
            const Real w = s.w[0][i] * s.w[1][j] * s.w[2][k] * P.mass[p];
            row[2 * k] += float(w * Real(change));
            row[2 * k + 1] += float(w);
          }
        }
    }
  }
}

} // namespace

void averageVolumeChange(const std::vector<MaterialGroup*>& groups, SparseGrid& grid, Real dt) {
  const size_t C = size_t(grid.channels.count);
  const int pairs[2] = {grid.channels.fbar, grid.channels.stateJ};
  const Real invDx = Real(1) / grid.dx;
  for (int colour = 0; colour < 8; ++colour) {
    const auto& blocks = grid.colours[size_t(colour)];
    // Blocks of one colour never reach the same node; they read velocities and write only the channels.
    tbb::parallel_for(tbb::blocked_range<size_t>(0, blocks.size(), 1), [&](const auto& r) {
      std::vector<Vec4> nodes(kPadNodes);
      std::vector<float> sums(4 * size_t(kPadNodes)); // per channel pair
      for (size_t c = r.begin(); c != r.end(); ++c) {
        const uint32_t b = blocks[c];
        const auto& up = grid.topology.upper(b);
        copyPaddedNodes(grid, up, nodes.data());
        std::fill(sums.begin(), sums.end(), 0.f);
        const BlockCoord& bc = grid.topology.coord(b);
        const int origin[3] = {bc.x * kBlockDim, bc.y * kBlockDim, bc.z * kBlockDim};
        for (const MaterialGroup* g : groups) {
          const size_t begin = g->blockStart[b], end = g->blockStart[b + 1];
          const int pair = g->averagesState() ? 1 : g->averagesVolume() && pairs[0] >= 0 ? 0 : -1;
          if (begin != end && pair >= 0)
            scatterVolumeChange(g->particles, pair ? g->averagedState() : nullptr, g->averagedStateMax(), begin, end,
                                nodes.data(), origin, dt, invDx, sums.data() + size_t(pair) * 2 * size_t(kPadNodes));
        }
        for (int pair = 0; pair < 2; ++pair) {
          if (pairs[pair] < 0) continue;
          forEachPaddedRow([&](int d, int pad, int node, int n) {
            float* out = grid.blockExtra(uint32_t(up[d])) + size_t(node) * C + size_t(pairs[pair]);
            const float* in = sums.data() + size_t(pair) * 2 * size_t(kPadNodes) + 2 * size_t(pad);
            for (int k = 0; k < n; ++k, out += C, in += 2) out[0] += in[0], out[1] += in[1];
          });
        }
      }
    });
  }
}

void copyMeanVolumeChange(const SparseGrid& grid, int channel, const std::array<int32_t, 8>& up, Real* out,
                          const PadBox& box) {
  const size_t C = size_t(grid.channels.count), ch = size_t(channel);
  forEachPaddedRow(box, [&](int d, int pad, int node, int n) {
    const float* in = grid.blockExtra(uint32_t(up[d])) + size_t(node) * C + ch;
    for (int k = 0; k < n; ++k, in += C) out[pad + k] = in[1] > 0.f ? Real(in[0] / in[1]) : Real(0);
  });
}

} // namespace talus
