#include "engine/transfer_g2p.h"

#include "engine/fbar.h"
#include "engine/sparse_grid.h"
#include "engine/stencil_lanes.h"
#include "engine/transfer_p2g.h"

#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

namespace talus {

namespace {

/// (0, velocity before forces) of the padded neighbourhood's nodes from P2G's momentum channels.
void copyOldVelocities(const SparseGrid& grid, const std::array<int32_t, 8>& up, const PadBox& box, Vec4* out) {
  const int C = grid.channels.count, m = grid.channels.momentum;
  forEachPaddedRow(box, [&](int d, int pad, int node, int n) {
    const Vec4* nodes = grid.block(uint32_t(up[d])) + node;
    const float* q = grid.blockExtra(uint32_t(up[d])) + size_t(node) * size_t(C) + size_t(m);
    for (int k = 0; k < n; ++k, q += C) {
      const Real mass = nodes[k][0];
      const Real inv = mass > Real(0) ? Real(1) / mass : Real(0);
      out[pad + k] << 0, inv * q[0], inv * q[1], inv * q[2];
    }
  });
}

} // namespace

void gatherChunkVelocities(const Vec4* nodes, const int origin[3], const QuadraticStencil* s, int n, Real invDx,
                           Vec3* vel, Mat3* C) {
#ifdef TALUS_DOUBLE
  for (int k = 0; k < n; ++k)
    gatherVelocity(nodes, s[k], s[k].base[0] - origin[0], s[k].base[1] - origin[1], s[k].base[2] - origin[2], invDx,
                   vel[k], C[k]);
#else
  StencilRows rows;
  for (int k = 0; k < n; ++k) {
    rows.first[k] = padIndex(s[k].base[0] - origin[0], s[k].base[1] - origin[1], s[k].base[2] - origin[2]);
    std::copy_n(&s[k].w[0][0], 9, &rows.w[k][0][0]);
  }
  GatheredRows sums;
  gatherRows(nodes[0].data(), rows, n, sums);
  const Real cScale = Real(4) * invDx; // D^-1 = 4/dx^2, times dx from the stencil offsets
  for (int k = 0; k < n; ++k) {
    // The three nodes of a row fold into one record; the first channel (mass) is junk.
    using Row = Eigen::Map<const Vec4, Eigen::Aligned16>;
    const float* a = sums.all[k];
    const Vec4 v = Row(a) + Row(a + 4) + Row(a + 8);
    const Vec4 bk = Row(a + 4) + Real(2) * Row(a + 8);
    const Vec4 bi = Row(sums.alongI[k]) + Row(sums.alongI[k] + 4) + Row(sums.alongI[k] + 8);
    const Vec4 bj = Row(sums.alongJ[k]) + Row(sums.alongJ[k] + 4) + Row(sums.alongJ[k] + 8);
    vel[k] = v.tail<3>();
    C[k].col(0) = cScale * (bi.tail<3>() - s[k].f[0] * vel[k]);
    C[k].col(1) = cScale * (bj.tail<3>() - s[k].f[1] * vel[k]);
    C[k].col(2) = cScale * (bk.tail<3>() - s[k].f[2] * vel[k]);
  }
#endif
}

void copyPaddedNodes(const SparseGrid& grid, const std::array<int32_t, 8>& up, Vec4* out, const PadBox& box) {
  forEachPaddedRow(box, [&](int d, int pad, int node, int n) { std::copy_n(grid.block(uint32_t(up[d])) + node, n, out + pad); });
}

G2PStats gridToParticles(const std::vector<MaterialGroup*>& groups, const SparseGrid& grid, Real dt, Real flip) {
  tbb::combinable<G2PStats> stats;
  const bool aflip = flip > Real(0) && grid.channels.momentum >= 0;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, grid.owning.size(), 1), [&](const auto& r) {
    std::vector<Vec4> buf(kPadNodes), old(aflip ? kPadNodes : 0);
    std::vector<Real> meanChange(grid.channels.fbar >= 0 ? kPadNodes : 0), meanJ(grid.channels.stateJ >= 0 ? kPadNodes : 0);
    G2PStats& st = stats.local();
    for (size_t o = r.begin(); o != r.end(); ++o) {
      const uint32_t b = grid.owning[o];
      // Copy the part of the padded neighbourhood the particles reach once; the per-particle loop
      // then indexes it densely.
      const auto& up = grid.topology.upper(b);
      const PadBox box = reachedNodes(groups, grid, b);
      copyPaddedNodes(grid, up, buf.data(), box);
      const BlockCoord& c = grid.topology.coord(b);
      G2PBlock blk{buf.data(), {c.x * kBlockDim, c.y * kBlockDim, c.z * kBlockDim}, dt, grid.dx,
                   Real(1) / grid.dx};
      if (aflip) {
        copyOldVelocities(grid, up, box, old.data());
        blk.old = old.data();
        blk.flip = flip;
      }
      if (grid.channels.fbar >= 0) copyMeanVolumeChange(grid, grid.channels.fbar, up, meanChange.data(), box);
      if (grid.channels.stateJ >= 0) copyMeanVolumeChange(grid, grid.channels.stateJ, up, meanJ.data(), box);
      for (MaterialGroup* g : groups) {
        const size_t begin = g->blockStart[b], end = g->blockStart[b + 1];
        if (begin == end) continue;
        blk.meanVolumeChange = g->averagesVolume() && !meanChange.empty() ? meanChange.data() : nullptr;
        blk.meanJ = g->averagesState() ? meanJ.data() : nullptr;
        g->gridToParticles(blk, begin, end, st);
      }
    }
  });
  G2PStats total;
  stats.combine_each([&](const G2PStats& s) { total.merge(s); });
  return total;
}

} // namespace talus
