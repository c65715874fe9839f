#include "io/output/node_scatter.h"

#include "engine/bspline.h"

#include <algorithm>
#include <tuple>
#include <unordered_map>

namespace talus {

namespace {
uint64_t blockKey(int x, int y, int z) {
  return (uint64_t(uint32_t(x) & 0x1fffff) << 42) | (uint64_t(uint32_t(y) & 0x1fffff) << 21) |
         uint64_t(uint32_t(z) & 0x1fffff);
}
} // namespace

NodeFields scatterNodeFields(const Simulation& sim) {
  NodeFields f;
  f.dx = sim.settings().dx;
  f.materials = int(sim.groups().size());
  const Real invDx = Real(1.0 / f.dx);

  // Pass 1: the blocks every stencil touches, sorted so files do not depend on particle order.
  std::unordered_map<uint64_t, uint32_t> index;
  for (const MaterialGroup* g : sim.groups())
    for (const Vec3& x : g->particles.x) {
      const QuadraticStencil s(x * invDx);
      const int lo[3] = {s.base[0] >> kBlockLog2, s.base[1] >> kBlockLog2, s.base[2] >> kBlockLog2};
      const int hi[3] = {(s.base[0] + 2) >> kBlockLog2, (s.base[1] + 2) >> kBlockLog2, (s.base[2] + 2) >> kBlockLog2};
      for (int bx = lo[0]; bx <= hi[0]; ++bx)
        for (int by = lo[1]; by <= hi[1]; ++by)
          for (int bz = lo[2]; bz <= hi[2]; ++bz)
            if (index.emplace(blockKey(bx, by, bz), 0).second) f.blocks.push_back({bx, by, bz});
    }
  std::sort(f.blocks.begin(), f.blocks.end(), [](const BlockCoord& a, const BlockCoord& b) {
    return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
  });
  for (size_t b = 0; b < f.blocks.size(); ++b) index[blockKey(f.blocks[b].x, f.blocks[b].y, f.blocks[b].z)] = uint32_t(b);
  f.mass.assign(f.blocks.size() * size_t(f.materials) * kBlockNodes, 0.f);
  f.momentum.assign(f.blocks.size() * kBlockNodes * 3, 0.f);

  // Pass 2: scatter. Frames are rare, so this stays serial and simple.
  for (int m = 0; m < f.materials; ++m) {
    const ParticleSet& P = sim.groups()[size_t(m)]->particles;
    for (size_t p = 0; p < P.size(); ++p) {
      const QuadraticStencil s(P.x[p] * invDx);
      const float mp = float(P.mass[p]);
      const Vec3 mv = P.mass[p] * P.v[p];
      // The 3^3 stencil spans 1, 2, 4 or 8 blocks: look each up once, not once per node.
      int b0[3], span[3];
      for (int d = 0; d < 3; ++d) {
        b0[d] = s.base[d] >> kBlockLog2;
        span[d] = ((s.base[d] + 2) >> kBlockLog2) - b0[d];
      }
      uint32_t blk[2][2][2] = {};
      for (int a = 0; a <= span[0]; ++a)
        for (int c = 0; c <= span[1]; ++c)
          for (int e = 0; e <= span[2]; ++e) blk[a][c][e] = index.at(blockKey(b0[0] + a, b0[1] + c, b0[2] + e));
      for (int i = 0; i < 3; ++i) {
        const int ni = s.base[0] + i, ai = (ni >> kBlockLog2) - b0[0];
        for (int j = 0; j < 3; ++j) {
          const int nj = s.base[1] + j, aj = (nj >> kBlockLog2) - b0[1];
          const float wij = float(s.w[0][i] * s.w[1][j]);
          for (int k = 0; k < 3; ++k) {
            const int nk = s.base[2] + k, ak = (nk >> kBlockLog2) - b0[2];
            const uint32_t b = blk[ai][aj][ak];
            const int node = blockNodeIndex(ni & (kBlockDim - 1), nj & (kBlockDim - 1), nk & (kBlockDim - 1));
            const float w = wij * float(s.w[2][k]);
            f.blockMass(b, m)[node] += w * mp;
            float* q = f.blockMomentum(b) + 3 * node;
            q[0] += w * float(mv[0]), q[1] += w * float(mv[1]), q[2] += w * float(mv[2]);
          }
        }
      }
    }
  }
  return f;
}

} // namespace talus
