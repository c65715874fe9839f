// The grid halo between MPI ranks: P2G contributions to blocks other ranks also hold.
//
// A rank holds its owning blocks and their +1 closure, as one process does. A node of that
// closure also gets contributions from particles of other ranks; each rank scatters its blocks
// whose stencils reach blocks active elsewhere ahead of P2G and sends those rows. A rank adds the
// rows it receives in the colour pass of the block that sent them, added in one process's order.
// A rank gets the rows its own particles' stencils reach (a face layer two nodes thick of a block
// it holds as closure, not the block's 512 nodes), and the rank counting a block (its owner, or
// the lowest holder of a block nobody owns) gets them all, so the nodes a rank reads in G2P and
// every node of a counted block hold the complete sum. The grid update on such a node runs on
// every rank holding it with identical inputs (no second exchange of velocities for G2P); its
// collider loads and thickness lines count on the counting rank only.
#pragma once

#include "engine/domain_decomposition.h"
#include "engine/padded_block.h"
#include "engine/sparse_grid.h"

#include <array>
#include <vector>

namespace talus {

/// Rows of part d (engine/padded_block.h) of another rank's padded buffer inside `box` (the
/// sender's padded coordinates, within part d), for local block `target`.
struct RemoteRows {
  int32_t target;
  int d;
  PadBox box;
  const char* nodes; ///< Vec4 per node, forEachPaddedRow order
  const char* extra; ///< extra channels per node, same order
};

class HaloExchange {
public:
  /// Collective, after binning, before particlesToGrid: learns the owning blocks next to this
  /// rank's from their ranks (not the whole grid's), scatters this rank's blocks that reach other
  /// ranks' blocks, and exchanges those rows.
  void exchange(const std::vector<MaterialGroup*>& groups, SparseGrid& grid, Real dt, DomainDecomposition& dd);

  /// The padded P2G buffer of owning block b scattered ahead, or null.
  const Vec4* stored(uint32_t b) const {
    return slot_[b] < 0 ? nullptr : stored_.data() + size_t(slot_[b]) * kPadNodes;
  }
  const float* storedExtra(uint32_t b) const {
    return storedExtra_.data() + size_t(slot_[b]) * kPadNodes * size_t(channels_);
  }
  const std::vector<RemoteRows>& remote(int colour) const { return remote_[size_t(colour)]; }
  /// Per active block: 1 when this rank counts the block's collider loads and thickness (its
  /// owner; for a block no rank owns, the lowest rank holding it). Only there are all 512 nodes
  /// complete on a rank that does not own the block.
  const std::vector<uint8_t>& counted() const { return counted_; }
  /// Halo bytes this rank sent in the last exchange, and the owning blocks it scattered ahead
  /// (those whose stencils reach blocks other ranks hold).
  size_t lastBytes() const { return lastBytes_; }
  size_t boundaryBlocks() const { return stored_.size() / kPadNodes; }

private:
  /// Rows of part d of owning block `block`'s padded buffer, inside `box`, for rank `rank`.
  struct Send {
    uint32_t block;
    int d, rank;
    PadBox box;
  };
  void pack(const Send& s, const SparseGrid& grid, std::vector<char>& out) const;
  /// remote_ from received_: each part's rows under the colour of the block that sent them.
  void indexReceived(const SparseGrid& grid);

  std::vector<int32_t> slot_;
  std::vector<Vec4> stored_;
  std::vector<float> storedExtra_;
  int channels_ = 0;
  std::array<std::vector<RemoteRows>, 8> remote_;
  std::vector<std::vector<char>> received_;
  std::vector<uint8_t> counted_;
  size_t lastBytes_ = 0;
};

} // namespace talus
