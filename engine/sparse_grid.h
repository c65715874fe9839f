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
  /// Extra per-node channels, scattered by P2G only when a collider's law needs them (the flow
  /// volume for thickness, per-material masses for mixed laws): `extraChannels` floats per node,
  /// node-major within block-major order. Per group g, extraOf[g] lists (channel, factor): the
  /// group adds factor * particle mass to the channel (1/rho: volume; 1: mass).
  int extraChannels = 0;
  std::vector<float> extra;
  std::vector<std::vector<std::pair<int, float>>> extraOf;
  /// First of 3 channels holding every particle's APIC momentum without the stress term (the grid
  /// velocity before forces, which the AFLIP blend's increment needs), or -1 when that is off.
  int momentumChannel = -1;
  /// First of 2 channels F-bar fills between the grid update and G2P (engine/fbar.h), or -1.
  int fbarChannel = -1;

  size_t blockCount() const { return topology.size(); }
  Vec4* block(uint32_t b) { return nodes.data() + size_t(b) * kBlockNodes; }
  const Vec4* block(uint32_t b) const { return nodes.data() + size_t(b) * kBlockNodes; }
  float* blockExtra(uint32_t b) { return extra.data() + size_t(b) * kBlockNodes * size_t(extraChannels); }
  const float* blockExtra(uint32_t b) const { return extra.data() + size_t(b) * kBlockNodes * size_t(extraChannels); }
  size_t memoryBytes() const {
    return topology.memoryBytes() + nodes.capacity() * sizeof(Vec4) + owning.capacity() * 4 +
           contactImpulse.capacity() * sizeof(double) + extra.capacity() * sizeof(float);
  }
};

} // namespace talus
