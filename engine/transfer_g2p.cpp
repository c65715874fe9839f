#include "engine/transfer_g2p.h"

#include "engine/sparse_grid.h"

#include <tbb/combinable.h>
#include <tbb/parallel_for.h>

namespace talus {

G2PStats gridToParticles(const std::vector<MaterialGroup*>& groups, const SparseGrid& grid, Real dt) {
  tbb::combinable<G2PStats> stats;
  tbb::parallel_for(tbb::blocked_range<size_t>(0, grid.owning.size(), 1), [&](const auto& r) {
    std::vector<Vec4> buf(kPadNodes);
    G2PStats& st = stats.local();
    for (size_t o = r.begin(); o != r.end(); ++o) {
      const uint32_t b = grid.owning[o];
      // Copy the padded neighbourhood once; the per-particle loop then indexes it densely.
      const auto& up = grid.topology.upper(b);
      forEachPaddedRow([&](int d, int pad, int node, int n) {
        std::copy_n(grid.block(uint32_t(up[d])) + node, n, buf.data() + pad);
      });
      const BlockCoord& c = grid.topology.coord(b);
      G2PBlock blk{buf.data(), {c.x * kBlockDim, c.y * kBlockDim, c.z * kBlockDim}, dt, grid.dx,
                   Real(1) / grid.dx};
      for (MaterialGroup* g : groups) {
        const size_t begin = g->blockStart[b], end = g->blockStart[b + 1];
        if (begin != end) g->gridToParticles(blk, begin, end, st);
      }
    }
  });
  G2PStats total;
  stats.combine_each([&](const G2PStats& s) { total.merge(s); });
  return total;
}

} // namespace talus
