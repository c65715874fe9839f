// Node data of the active blocks: contiguous arrays of 512 nodes per block.
#pragma once

#include "engine/block_topology.h"
#include "engine/types.h"

#include <array>
#include <vector>

namespace talus {

struct SparseGrid {
  Real dx = 1;
  BlockTopology topology;
  std::vector<Vec4> nodes;               ///< size() * 512 nodes, block-major
  std::vector<uint32_t> owning;          ///< active blocks that hold particles
  std::array<std::vector<uint32_t>, 8> colours; ///< owning blocks by blockColour
  std::vector<double> contactImpulse;     ///< grid update scratch: per block and collider, impulse and moment

  size_t blockCount() const { return topology.size(); }
  Vec4* block(uint32_t b) { return nodes.data() + size_t(b) * kBlockNodes; }
  const Vec4* block(uint32_t b) const { return nodes.data() + size_t(b) * kBlockNodes; }
  size_t memoryBytes() const {
    return topology.memoryBytes() + nodes.capacity() * sizeof(Vec4) + owning.capacity() * 4 +
           contactImpulse.capacity() * sizeof(double);
  }
};

} // namespace talus
