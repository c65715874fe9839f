// The padded 10^3 neighbourhood of a block: the nodes its particles' stencils reach, made of the
// block itself and parts of its 7 upper neighbours (engine/block_topology.h, `upper`). P2G
// scatters into such a buffer and adds it to the eight blocks; G2P copies the eight parts into
// one; frame output scatters per-material masses the same way.
#pragma once

#include "engine/types.h"

#include <algorithm>

namespace talus {

/// Padded block edge: a block's particles reach nodes 0..9 from its origin.
constexpr int kPad = kBlockDim + 2;
constexpr int kPadNodes = kPad * kPad * kPad;
inline constexpr int padIndex(int i, int j, int k) { return (i * kPad + j) * kPad + k; }

/// The part of a padded neighbourhood a block's particles reach: padded nodes lo..hi per axis
/// (inclusive). The default is the whole neighbourhood. A thin flow reaches a fraction of it
/// (Wolfsgruben at dx 5 m: 430 of 1000 nodes on average), so P2G and G2P clear, add and copy only this part.
struct PadBox {
  int lo[3] = {0, 0, 0}, hi[3] = {kPad - 1, kPad - 1, kPad - 1};
};

/// Calls f(d, padStart, nodeStart, n) for every x-y row of the padded buffer inside `box`: n nodes
/// along z from padIndex `padStart` correspond to the nodes from blockNodeIndex `nodeStart` of
/// neighbour d (d in 0..7: bit 2 = +x, bit 1 = +y, bit 0 = +z, as BlockTopology::upper).
template <class F>
inline void forEachPaddedRow(const PadBox& box, F&& f) {
  for (int d = 0; d < 8; ++d) {
    const int ox = (d >> 2) * kBlockDim, oy = ((d >> 1) & 1) * kBlockDim, oz = (d & 1) * kBlockDim;
    const int nx = (d >> 2) ? 2 : kBlockDim, ny = ((d >> 1) & 1) ? 2 : kBlockDim, nz = (d & 1) ? 2 : kBlockDim;
    const int i0 = std::max(ox, box.lo[0]), i1 = std::min(ox + nx - 1, box.hi[0]);
    const int j0 = std::max(oy, box.lo[1]), j1 = std::min(oy + ny - 1, box.hi[1]);
    const int k0 = std::max(oz, box.lo[2]), k1 = std::min(oz + nz - 1, box.hi[2]);
    if (k1 < k0) continue;
    for (int i = i0; i <= i1; ++i)
      for (int j = j0; j <= j1; ++j) f(d, padIndex(i, j, k0), blockNodeIndex(i - ox, j - oy, k0 - oz), k1 - k0 + 1);
  }
}

/// The same over the whole padded neighbourhood.
template <class F>
inline void forEachPaddedRow(F&& f) {
  forEachPaddedRow(PadBox{}, f);
}

} // namespace talus
