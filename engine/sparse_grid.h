// Node data of the active blocks: contiguous arrays of 512 nodes per block.
#pragma once

#include "engine/block_topology.h"
#include "engine/types.h"

#include <array>
#include <vector>

namespace talus {

/// The extra float channels a node carries beyond mass and momentum, each only when the scene
/// needs it: every index is the channel's first float in a node's record, or -1 when unused.
struct ExtraChannels {
  int count = 0;       ///< floats per node
  int thickness = -1;  ///< the flow's volume (particle mass / density), for the thickness laws
  int momentum = -1;   ///< 3: every particle's APIC momentum without the stress term (AFLIP's
                       ///< grid velocity before forces)
  int fbar = -1;       ///< 2: F-bar's m (dJ - 1) and m, filled between the grid update and G2P
  int stateJ = -1;     ///< 2: the same for m (J - 1) and m of the materials that average their J
                       ///< (MaterialGroup::averagesState), apart: a state and an increment do not mix
  /// Per group: the (channel, factor) pairs P2G adds factor * particle mass to (1/rho into
  /// `thickness`, 1 into the node mass of a material with its own basal law, MaterialLaw::channel).
  std::vector<std::vector<std::pair<int, float>>> scatterOf;
};

struct SparseGrid {
  Real dx = 1;
  BlockTopology topology;
  std::vector<Vec4> nodes;               ///< size() * 512 nodes, block-major
  std::vector<uint32_t> owning;          ///< active blocks that hold particles
  std::array<std::vector<uint32_t>, 8> colours; ///< owning blocks by blockColour
  std::vector<double> contactImpulse;     ///< grid update scratch: per block and collider, impulse and moment
  /// P2G's extra per-node float channels, by name (ExtraChannels), node-major within block-major
  /// order: `channels.count` floats per node.
  ExtraChannels channels;
  std::vector<float> extra;

  size_t blockCount() const { return topology.size(); }
  Vec4* block(uint32_t b) { return nodes.data() + size_t(b) * kBlockNodes; }
  const Vec4* block(uint32_t b) const { return nodes.data() + size_t(b) * kBlockNodes; }
  float* blockExtra(uint32_t b) { return extra.data() + size_t(b) * kBlockNodes * size_t(channels.count); }
  const float* blockExtra(uint32_t b) const { return extra.data() + size_t(b) * kBlockNodes * size_t(channels.count); }
  size_t memoryBytes() const {
    return topology.memoryBytes() + nodes.capacity() * sizeof(Vec4) + owning.capacity() * 4 +
           contactImpulse.capacity() * sizeof(double) + extra.capacity() * sizeof(float);
  }
};

} // namespace talus
