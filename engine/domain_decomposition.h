// Which rank owns which blocks: contiguous ranges of blocks in the tree's order (BlockTopology's
// block order), sized by particle count, and the migration of particles between ranks.
//
// Why the tree's order: one process sorts particles by block in exactly that order (stably), so
// when rank r holds the r-th range, the ranks' particle arrays concatenated in rank order are the
// one process's arrays. Migration keeps that true: a rank rebuilds its arrays from what the
// ranks below it sent, then its own, then what the ranks above sent, and binning's stable sort
// does the rest. Every sum on the grid then sees the same particles in the same order.
#pragma once

#include "engine/communicator.h"
#include "engine/material_group.h"
#include "engine/particle_binning.h"

#include <array>
#include <memory>
#include <vector>

namespace talus {

/// Strict weak order of block coordinates identical to the iteration order of BlockTopology's
/// OpenVDB tree (Int32Tree: root tiles of 4096^3 blocks in coordinate order, then 32^3 and 16^3
/// children and 8^3 leaf voxels, each x-major).
inline bool treeOrderLess(const BlockCoord& a, const BlockCoord& b) {
  auto root = [](const BlockCoord& c) { return std::array<int32_t, 3>{c.x >> 12, c.y >> 12, c.z >> 12}; };
  const auto ra = root(a), rb = root(b);
  if (ra != rb) return ra < rb;
  auto inner = [](const BlockCoord& c) {
    auto part = [&](int shift, int mask, int bits) {
      return (uint64_t((c.x >> shift) & mask) << (2 * bits)) | (uint64_t((c.y >> shift) & mask) << bits) |
             uint64_t((c.z >> shift) & mask);
    };
    return (part(7, 31, 5) << 21) | (part(3, 15, 4) << 9) | part(0, 7, 3);
  };
  return inner(a) < inner(b);
}

/// Particles idx of g (common arrays and model state) as records of
/// ParticleSet::bytesPerParticle() + g.stateBytesPerParticle() bytes; and records appended to g.
void packParticles(const MaterialGroup& g, const std::vector<uint32_t>& idx, std::vector<char>& out);
void appendParticles(MaterialGroup& g, std::string_view in);
inline void appendParticles(MaterialGroup& g, const std::vector<char>& in) {
  appendParticles(g, std::string_view(in.data(), in.size()));
}
/// Particles idx of g, each with its key keys[idx[i]] (its index in one process's arrays): the
/// keys, then the records. And such parts, from any ranks, appended to g in the order of their keys
/// (DomainDecomposition::scatterSeeded, Simulation::gatherSeededInto).
void packKeyed(const MaterialGroup& g, const std::vector<uint32_t>& idx, const std::vector<uint64_t>& keys,
               std::vector<char>& out);
void appendInKeyOrder(MaterialGroup& g, const std::vector<std::string_view>& parts);

class DomainDecomposition {
public:
  /// @param imbalance  rebalance when the most loaded rank holds more than (1 + imbalance) times
  ///                   the mean particle count
  DomainDecomposition(std::shared_ptr<Communicator> comm, double imbalance);

  Communicator& comm() const { return *comm_; }
  int rank() const { return comm_->rank(); }
  int size() const { return comm_->size(); }
  /// Rank owning block c.
  int owner(const BlockCoord& c) const;
  /// Changes whenever the ranges do (each balance()): caches of owner() compare it.
  uint64_t generation() const { return generation_; }

  /// Collective. New ranges from the global owning blocks and their particle counts (any order):
  /// rank r gets the blocks whose cumulative count, in tree order, starts in [r, r+1) N/size,
  /// or in its share of N after setShares.
  void balance(std::vector<std::pair<BlockCoord, uint64_t>> blocks);
  /// The fraction of the particles each rank should own (size() values >= 0, summing to 1; the
  /// same on every rank). Empty: equal shares. Used by the next balance and imbalance; the
  /// results do not depend on the ranges, only the time does.
  void setShares(std::vector<double> shares);
  /// Collective. Moves every particle to the rank owning its block (see the file comment).
  /// Returns the number of particles this rank sent away. The next binning must take order().
  /// @param fresh  per group, particles made at the arrays' end since the last binning, each on
  ///               the rank owning its block (they stay): ordered after every rank's others
  size_t migrate(const std::vector<MaterialGroup*>& groups, Real dx, const std::vector<size_t>* fresh = nullptr);
  /// Per group, the order binning's stable sort must follow after migrate (empty: the arrays').
  const std::vector<ParticleOrder>& order() const { return order_; }
  /// Keeps only the particles of this rank's blocks (every rank holding every particle).
  void keepOwn(const std::vector<MaterialGroup*>& groups, Real dx);
  /// Collective, when each rank seeded a part of the scene: moves every particle to the rank
  /// owning its block and orders each rank's particles by `index` (per MaterialGroup::index(),
  /// each particle's index in one process's arrays), so they are in one process's order.
  void scatterSeeded(const std::vector<MaterialGroup*>& groups, Real dx,
                     const std::vector<std::vector<uint64_t>>& index);

  /// Collective: (max / target - 1) of the ranks' particle counts; the target is the mean, or
  /// the rank's share of the total.
  double imbalance(size_t localParticles) const;
  /// The same from every rank's count (counts[r]: rank r's), without a collective.
  double imbalanceOf(const std::vector<double>& counts) const;
  double threshold() const { return threshold_; }
  /// Called once per step: whether an imbalance calls for new ranges. Above the threshold by
  /// more than what the last ranges left, or above it at all kRetrySteps steps after them (blocks
  /// are indivisible, so a few heavy blocks can keep a rank above the threshold whatever the
  /// ranges: rebalancing at every step then buys nothing; as the flow spreads over more blocks
  /// the retry finds the better ranges).
  static constexpr int kRetrySteps = 64;
  bool wantsRebalance(double imbalance);
  uint64_t rebalances = 0;

private:
  std::shared_ptr<Communicator> comm_;
  double threshold_;
  double settled_ = 0; ///< the imbalance the last balance() left
  int sinceBalance_ = 0; ///< steps since then
  std::vector<BlockCoord> first_; ///< first block of ranks 1..size-1
  uint64_t generation_ = 0;
  std::vector<double> shares_;    ///< empty: equal
  std::vector<ParticleOrder> order_;
};

} // namespace talus
