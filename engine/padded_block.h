// The padded 10^3 neighbourhood of a block: the nodes its particles' stencils reach, made of the
// block itself and parts of its 7 upper neighbours (engine/block_topology.h, `upper`). P2G
// scatters into such a buffer and adds it to the eight blocks; G2P copies the eight parts into
// one; frame output scatters per-material masses the same way.
#pragma once

#include "engine/types.h"

namespace talus {

/// Padded block edge: a block's particles reach nodes 0..9 from its origin.
constexpr int kPad = kBlockDim + 2;
constexpr int kPadNodes = kPad * kPad * kPad;
inline constexpr int padIndex(int i, int j, int k) { return (i * kPad + j) * kPad + k; }

/// Calls f(d, padStart, nodeStart, n) for every x-y row of the padded buffer: n nodes along z
/// from padIndex `padStart` correspond to the nodes from blockNodeIndex `nodeStart` of neighbour d
/// (d in 0..7: bit 2 = +x, bit 1 = +y, bit 0 = +z, as BlockTopology::upper).
template <class F>
inline void forEachPaddedRow(F&& f) {
  for (int d = 0; d < 8; ++d) {
    const int ox = (d >> 2) * kBlockDim, oy = ((d >> 1) & 1) * kBlockDim, oz = (d & 1) * kBlockDim;
    const int nx = (d >> 2) ? 2 : kBlockDim, ny = ((d >> 1) & 1) ? 2 : kBlockDim, nz = (d & 1) ? 2 : kBlockDim;
    for (int i = 0; i < nx; ++i)
      for (int j = 0; j < ny; ++j) f(d, padIndex(ox + i, oy + j, oz), blockNodeIndex(i, j, 0), nz);
  }
}

} // namespace talus
