#include "io/output/node_scatter.h"

#include "engine/bspline.h"
#include "engine/padded_block.h"

#include <algorithm>
#include <tuple>
#include <unordered_map>

namespace talus {

NodeFields scatterNodeFields(const Simulation& sim) {
  NodeFields f;
  f.dx = sim.settings().dx;
  f.materials = int(sim.groups().size());
  const Real invDx = Real(1.0 / f.dx);
  const int channels = f.materials + 3; // mass per material, then momentum

  // Particles by owning block (the block of their stencil's base node), in particle order.
  struct Owned {
    int material;
    uint32_t particle;
  };
  std::unordered_map<uint64_t, size_t> ownerIndex;
  std::vector<BlockCoord> owners;
  std::vector<std::vector<Owned>> owned;
  for (int m = 0; m < f.materials; ++m) {
    const ParticleSet& P = sim.groups()[size_t(m)]->particles;
    for (size_t p = 0; p < P.size(); ++p) {
      const BlockCoord c = owningBlock(P.x[p], invDx);
      const auto [it, fresh] = ownerIndex.emplace(blockKey(c), owners.size());
      if (fresh) owners.push_back(c), owned.emplace_back();
      owned[it->second].push_back({m, uint32_t(p)});
    }
  }
  // Every block a stencil can reach, sorted so files do not depend on particle order.
  std::unordered_map<uint64_t, uint32_t> index;
  for (const BlockCoord& c : owners)
    for (int d = 0; d < 8; ++d) {
      const BlockCoord n{c.x + (d >> 2), c.y + ((d >> 1) & 1), c.z + (d & 1)};
      if (index.emplace(blockKey(n), 0).second) f.blocks.push_back(n);
    }
  std::sort(f.blocks.begin(), f.blocks.end(), [](const BlockCoord& a, const BlockCoord& b) {
    return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z);
  });
  for (size_t b = 0; b < f.blocks.size(); ++b) index[blockKey(f.blocks[b])] = uint32_t(b);
  f.mass.assign(f.blocks.size() * size_t(f.materials) * kBlockNodes, 0.f);
  f.momentum.assign(f.blocks.size() * kBlockNodes * 3, 0.f);

  // Scatter each owning block's particles into a padded buffer, then add it to the eight blocks.
  // Frames are rare, so this stays serial and simple.
  std::vector<float> buf(size_t(kPadNodes) * size_t(channels));
  for (size_t o = 0; o < owners.size(); ++o) {
    std::fill(buf.begin(), buf.end(), 0.f);
    const BlockCoord& oc = owners[o];
    const int origin[3] = {oc.x * kBlockDim, oc.y * kBlockDim, oc.z * kBlockDim};
    for (const Owned& q : owned[o]) {
      const ParticleSet& P = sim.groups()[size_t(q.material)]->particles;
      const QuadraticStencil s(P.x[q.particle] * invDx);
      const float mp = float(P.mass[q.particle]);
      const Vec3 mv = P.mass[q.particle] * P.v[q.particle];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const float wij = float(s.w[0][i] * s.w[1][j]);
          for (int k = 0; k < 3; ++k) {
            const float w = wij * float(s.w[2][k]);
            float* node = buf.data() + size_t(padIndex(s.base[0] - origin[0] + i, s.base[1] - origin[1] + j,
                                                       s.base[2] - origin[2] + k)) * size_t(channels);
            node[q.material] += w * mp;
            for (int d = 0; d < 3; ++d) node[f.materials + d] += w * float(mv[d]);
          }
        }
    }
    uint32_t dest[8];
    for (int d = 0; d < 8; ++d) dest[d] = index.at(blockKey({oc.x + (d >> 2), oc.y + ((d >> 1) & 1), oc.z + (d & 1)}));
    forEachPaddedRow([&](int d, int pad, int node, int n) {
      for (int k = 0; k < n; ++k) {
        const float* src = buf.data() + size_t(pad + k) * size_t(channels);
        for (int m = 0; m < f.materials; ++m) f.blockMass(dest[d], m)[node + k] += src[m];
        float* q = f.blockMomentum(dest[d]) + 3 * (node + k);
        for (int c = 0; c < 3; ++c) q[c] += src[f.materials + c];
      }
    });
  }
  // Keep only blocks that received mass.
  size_t kept = 0;
  for (size_t b = 0; b < f.blocks.size(); ++b) {
    const float* m0 = f.blockMass(b, 0);
    if (std::none_of(m0, m0 + size_t(f.materials) * kBlockNodes, [](float v) { return v > 0; })) continue;
    if (kept != b) {
      f.blocks[kept] = f.blocks[b];
      std::copy_n(m0, size_t(f.materials) * kBlockNodes, f.blockMass(kept, 0));
      std::copy_n(f.blockMomentum(b), kBlockNodes * 3, f.blockMomentum(kept));
    }
    ++kept;
  }
  f.blocks.resize(kept);
  f.mass.resize(kept * size_t(f.materials) * kBlockNodes);
  f.momentum.resize(kept * kBlockNodes * 3);
  return f;
}

} // namespace talus
