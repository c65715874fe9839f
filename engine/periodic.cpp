#include "engine/periodic.h"

#include <algorithm>
#include <cmath>
#include <tbb/parallel_for.h>

namespace talus {

namespace {
int component(const BlockCoord& c, int a) { return a == 0 ? c.x : a == 1 ? c.y : c.z; }
int& component(BlockCoord& c, int a) { return a == 0 ? c.x : a == 1 ? c.y : c.z; }
int nodeIndex(int n, int a) { return a == 0 ? n >> (2 * kBlockLog2) : a == 1 ? (n >> kBlockLog2) & 7 : n & 7; }

/// Calls f(ghostBlock, imageBlock) for every active block holding ghost nodes along axis a, with
/// `shift` = -1 (ghosts above the period) or +1 (below).
template <class F> void forGhostBlocks(const Periodicity& p, const SparseGrid& grid, int a, F&& f) {
  BlockTopology::Lookup lookup(grid.topology);
  const int blocks = p.n[a] / kBlockDim;
  for (uint32_t b = 0; b < grid.blockCount(); ++b) {
    const BlockCoord& c = grid.topology.coord(b);
    const int first = component(c, a) * kBlockDim, last = first + kBlockDim - 1;
    for (int side : {-1, 1}) {
      const bool ghosts = side < 0 ? last >= p.lo[a] + p.n[a] : first < p.lo[a];
      if (!ghosts) continue;
      BlockCoord img = c;
      component(img, a) += side * blocks;
      const int32_t i = lookup.find(img);
      if (i >= 0) f(b, uint32_t(i), side);
    }
  }
}

bool isGhost(const Periodicity& p, int a, const BlockCoord& c, int n, int side) {
  const int idx = component(c, a) * kBlockDim + nodeIndex(n, a);
  return side < 0 ? idx >= p.lo[a] + p.n[a] : idx < p.lo[a];
}
} // namespace

void Periodicity::addImages(std::vector<BlockCoord>& blocks) const {
  const size_t n0 = blocks.size();
  for (int a = 0; a < 3; ++a) {
    if (!axis[a]) continue;
    const size_t count = blocks.size();
    for (size_t i = 0; i < count; ++i)
      for (int d = 0; d < 8; ++d) { // the block's +1 closure is where P2G may write
        BlockCoord c{blocks[i].x + (d >> 2), blocks[i].y + ((d >> 1) & 1), blocks[i].z + (d & 1)};
        const int first = component(c, a) * kBlockDim;
        if (first + kBlockDim - 1 >= lo[a] + n[a]) component(c, a) -= n[a] / kBlockDim, blocks.push_back(c);
        else if (first < lo[a]) component(c, a) += n[a] / kBlockDim, blocks.push_back(c);
      }
  }
  (void)n0;
}

void Periodicity::fold(SparseGrid& grid) const {
  const int C = grid.channels.count;
  for (int a = 0; a < 3; ++a) {
    if (!axis[a]) continue;
    // Serial: a few faces of blocks, and the same order at any thread count.
    forGhostBlocks(*this, grid, a, [&](uint32_t ghost, uint32_t image, int side) {
      const BlockCoord& c = grid.topology.coord(ghost);
      Vec4* g = grid.block(ghost);
      Vec4* im = grid.block(image);
      for (int n = 0; n < kBlockNodes; ++n) {
        if (!isGhost(*this, a, c, n, side)) continue;
        im[n] += g[n];
        g[n].setZero();
        if (C > 0) {
          float* ge = grid.blockExtra(ghost) + size_t(n) * size_t(C);
          float* ie = grid.blockExtra(image) + size_t(n) * size_t(C);
          for (int k = 0; k < C; ++k) ie[k] += ge[k], ge[k] = 0;
        }
      }
    });
  }
}

void Periodicity::unfold(SparseGrid& grid) const {
  // The extra channels too: G2P reads AFLIP's momentum channels on ghost nodes.
  const int C = grid.channels.count;
  for (int a = 2; a >= 0; --a) { // the reverse of fold, so corner ghosts get their final images
    if (!axis[a]) continue;
    forGhostBlocks(*this, grid, a, [&](uint32_t ghost, uint32_t image, int side) {
      const BlockCoord& c = grid.topology.coord(ghost);
      Vec4* g = grid.block(ghost);
      const Vec4* im = grid.block(image);
      for (int n = 0; n < kBlockNodes; ++n) {
        if (!isGhost(*this, a, c, n, side)) continue;
        g[n] = im[n];
        if (C > 0)
          std::copy_n(grid.blockExtra(image) + size_t(n) * size_t(C), C, grid.blockExtra(ghost) + size_t(n) * size_t(C));
      }
    });
  }
}

Real Periodicity::wrap(int a, Real x, Real dx) const {
  const Real lo0 = Real(lo[a]) * dx, len = Real(n[a]) * dx;
  if (x >= lo0 + len) return x - len;
  if (x < lo0) return x + len;
  return x;
}

} // namespace talus
