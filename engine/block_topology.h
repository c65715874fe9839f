// Which 8^3 blocks of grid nodes are active, held in an OpenVDB tree.
//
// The tree lives in block coordinates: one voxel per block, its value the block's index into
// the engine's contiguous node arrays. Rebuilt every step from the blocks that own particles
// plus the +x/+y/+z closure their quadratic stencils reach, so grid memory follows the material,
// not the domain's bounding box. Block indices follow the tree's own (spatially coherent,
// deterministic) order. OpenVDB stays inside block_topology.cpp.
#pragma once

#include "engine/types.h"

#include <array>
#include <memory>
#include <vector>

namespace talus {

class BlockTopology {
public:
  BlockTopology();
  ~BlockTopology();
  BlockTopology(const BlockTopology&) = delete;
  BlockTopology& operator=(const BlockTopology&) = delete;

  /// Active blocks = owning blocks and every block + (0|1, 0|1, 0|1) from them.
  void rebuild(const std::vector<BlockCoord>& owning);

  size_t size() const { return coords_.size(); }
  const BlockCoord& coord(uint32_t b) const { return coords_[b]; }
  /// Index of block b + (dx, dy, dz) for the 8 offsets in {0,1}^3 (bit 2 = x, 1 = y, 0 = z), or -1.
  const std::array<int32_t, 8>& upper(uint32_t b) const { return upper_[b]; }

  /// Thread-private lookup of block indices (wraps an OpenVDB value accessor).
  class Lookup {
  public:
    explicit Lookup(const BlockTopology& t);
    ~Lookup();
    int32_t find(const BlockCoord& c); ///< -1 when not active
  private:
    struct Impl;
    std::unique_ptr<Impl> impl_;
  };

  size_t memoryBytes() const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  std::vector<BlockCoord> coords_;
  std::vector<std::array<int32_t, 8>> upper_;
  friend class Lookup;
};

inline int blockColour(const BlockCoord& c) { return ((c.x & 1) << 2) | ((c.y & 1) << 1) | (c.z & 1); }

} // namespace talus
