#include "engine/block_topology.h"

#include <openvdb/openvdb.h>
#include <tbb/parallel_for.h>

namespace talus {

using IndexTree = openvdb::Int32Tree;

struct BlockTopology::Impl {
  IndexTree tree{-1};
};

struct BlockTopology::Lookup::Impl {
  explicit Impl(const IndexTree& t) : acc(t) {}
  openvdb::tree::ValueAccessor<const IndexTree> acc;
};

BlockTopology::BlockTopology() : impl_(std::make_unique<Impl>()) {}
BlockTopology::~BlockTopology() = default;

void BlockTopology::rebuild(const std::vector<BlockCoord>& owning) {
  IndexTree& tree = impl_->tree;
  {
    // The last rebuild's blocks are switched off (value -1, the background) instead of clearing
    // the tree: clear() frees its nodes, and allocating and zeroing them again every step (the
    // top internal node alone is 256 KB) cost up to several ms a step whatever the scene's size
    // (page faults in memset: a 64-particle bar 0.24 -> 0.015 s, docs/throughput.md). The nodes
    // kept are those the flow has ever touched (4 bytes per block); the iteration below visits
    // active values only, and the blocks switched off read -1 as before.
    openvdb::tree::ValueAccessor<IndexTree> acc(tree);
    for (const BlockCoord& c : coords_) acc.setValueOff(openvdb::Coord(c.x, c.y, c.z), -1);
    for (const BlockCoord& c : owning)
      for (int d = 0; d < 8; ++d)
        acc.setValueOn(openvdb::Coord(c.x + (d >> 2), c.y + ((d >> 1) & 1), c.z + (d & 1)), 0);
  }
  coords_.clear();
  coords_.reserve(tree.activeVoxelCount());
  int32_t index = 0;
  for (auto it = tree.beginValueOn(); it; ++it) {
    const openvdb::Coord& c = it.getCoord();
    coords_.push_back({c.x(), c.y(), c.z()});
    it.setValue(index++);
  }
  upper_.resize(coords_.size());
  tbb::parallel_for(tbb::blocked_range<size_t>(0, coords_.size(), 256), [&](const auto& r) {
    openvdb::tree::ValueAccessor<const IndexTree> acc(tree);
    for (size_t b = r.begin(); b != r.end(); ++b) {
      const BlockCoord& c = coords_[b];
      for (int d = 0; d < 8; ++d)
        upper_[b][d] = acc.getValue(openvdb::Coord(c.x + (d >> 2), c.y + ((d >> 1) & 1), c.z + (d & 1)));
    }
  });
}

size_t BlockTopology::memoryBytes() const {
  return size_t(impl_->tree.memUsage()) + coords_.capacity() * sizeof(BlockCoord) +
         upper_.capacity() * sizeof(upper_[0]);
}

BlockTopology::Lookup::Lookup(const BlockTopology& t) : impl_(std::make_unique<Impl>(t.impl_->tree)) {}
BlockTopology::Lookup::~Lookup() = default;

int32_t BlockTopology::Lookup::find(const BlockCoord& c) {
  return impl_->acc.getValue(openvdb::Coord(c.x, c.y, c.z));
}

} // namespace talus
