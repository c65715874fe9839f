#include "engine/halo_exchange.h"

#include "engine/padded_block.h"
#include "engine/transfer_p2g.h"

#include <algorithm>
#include <array>
#include <cstring>
#include <stdexcept>
#include <tbb/parallel_for.h>
#include <unordered_map>

namespace talus {

namespace {

BlockCoord offset(const BlockCoord& c, int d, int sign) {
  return {c.x + sign * (d >> 2), c.y + sign * ((d >> 1) & 1), c.z + sign * (d & 1)};
}

/// Part d of a padded buffer (the block itself: 8^3 nodes; a face: 2 x 8 x 8; ...).
PadBox partBox(int d) {
  PadBox box;
  for (int a = 0; a < 3; ++a) {
    const int up = (d >> (2 - a)) & 1;
    box.lo[a] = up ? kBlockDim : 0;
    box.hi[a] = up ? kPad - 1 : kBlockDim - 1;
  }
  return box;
}

int boxNodes(const PadBox& box) {
  return (box.hi[0] - box.lo[0] + 1) * (box.hi[1] - box.lo[1] + 1) * (box.hi[2] - box.lo[2] + 1);
}

struct Header {
  int32_t x, y, z, d;
  int8_t lo[3], hi[3], unused[2];
};

/// The owning blocks within one block of this rank's, with their ranks: what the halo must know
/// of the rest of the grid. Ranges say which rank owns a coordinate (dd.owner), but only that
/// rank knows whether the block holds particles: each rank tells its owning blocks to the ranks
/// owning one of their 26 neighbours. That is every block holders() asks about (X - {0,1}^3 for
/// X within +1 of this rank's blocks), and no more. Collective.
class NeighbourRanks {
public:
  NeighbourRanks(const SparseGrid& grid, DomainDecomposition& dd) : size_(dd.comm().size()) {
    const int me = dd.comm().rank();
    std::vector<std::vector<char>> tell(static_cast<size_t>(size_));
    for (uint32_t b : grid.owning) {
      const BlockCoord& c = grid.topology.coord(b);
      std::array<int, 26> told{};
      int k = 0;
      for (int dz = -1; dz <= 1; ++dz)
        for (int dy = -1; dy <= 1; ++dy)
          for (int dx = -1; dx <= 1; ++dx) {
            const int r = dd.owner({c.x + dx, c.y + dy, c.z + dz});
            if (r == me || std::find(told.begin(), told.begin() + k, r) != told.begin() + k) continue;
            told[size_t(k++)] = r;
            auto& t = tell[size_t(r)];
            t.insert(t.end(), reinterpret_cast<const char*>(&c), reinterpret_cast<const char*>(&c) + sizeof(c));
          }
    }
    const std::vector<std::vector<char>> heard = dd.comm().exchange(tell);
    rankOf_.reserve(grid.owning.size() * 2);
    for (uint32_t b : grid.owning) rankOf_.emplace(blockKey(grid.topology.coord(b)), me);
    for (int r = 0; r < size_; ++r)
      for (size_t at = 0; at + sizeof(BlockCoord) <= heard[size_t(r)].size(); at += sizeof(BlockCoord)) {
        BlockCoord c;
        std::memcpy(&c, heard[size_t(r)].data() + at, sizeof(c));
        rankOf_.emplace(blockKey(c), r);
      }
  }

  /// The owner of block X, or -1.
  int owner(const BlockCoord& X) const {
    const auto it = rankOf_.find(blockKey(X));
    return it == rankOf_.end() ? -1 : it->second;
  }

  /// The ranks holding block X (those owning one of X - {0,1}^3) into out; returns their count.
  int holders(const BlockCoord& X, std::array<int, 8>& out) const {
    int k = 0;
    for (int e = 0; e < 8; ++e) {
      const int r = owner(offset(X, e, -1));
      if (r >= 0 && std::find(out.begin(), out.begin() + k, r) == out.begin() + k) out[size_t(k++)] = r;
    }
    return k;
  }

  /// The rank counting block X (loads, thickness lines): its owner; for a block nobody owns, the
  /// lowest rank holding it. Every rank holding X computes the same.
  int counting(const BlockCoord& X) const {
    if (const int r = owner(X); r >= 0) return r;
    std::array<int, 8> h{};
    const int k = holders(X, h);
    return k ? *std::min_element(h.begin(), h.begin() + k) : size_;
  }

  /// The rows of part d (X = Y + d) a rank holding X without counting it reads in G2P: from its
  /// block X - e, all of X along the axes where e is 0 and the first two node layers where e is
  /// 1. The bounding box of those, in Y's padded coordinates.
  PadBox reach(const BlockCoord& X, int rank, int d) const {
    int hi[3] = {1, 1, 1};
    for (int e = 0; e < 8; ++e)
      if (owner(offset(X, e, -1)) == rank)
        for (int a = 0; a < 3; ++a)
          if (!((e >> (2 - a)) & 1)) hi[a] = kBlockDim - 1;
    PadBox box = partBox(d);
    for (int a = 0; a < 3; ++a)
      if (!((d >> (2 - a)) & 1)) box.hi[a] = hi[a];
    return box;
  }

private:
  int size_;
  std::unordered_map<uint64_t, int> rankOf_;
};

} // namespace

void HaloExchange::exchange(const std::vector<MaterialGroup*>& groups, SparseGrid& grid, Real dt,
                            DomainDecomposition& dd) {
  Communicator& comm = dd.comm();
  const int me = comm.rank(), n = comm.size();
  const size_t nBlocks = grid.blockCount();
  channels_ = std::max(grid.channels.count, 0);
  const NeighbourRanks ranks(grid, dd);

  counted_.assign(nBlocks, 0);
  for (size_t b = 0; b < nBlocks; ++b) counted_[b] = ranks.counting(grid.topology.coord(uint32_t(b))) == me;

  // Owning blocks whose parts other ranks hold: (block, part, rank, rows). The rank counting the
  // target gets the part whole, the others what they read.
  std::vector<Send> sends;
  slot_.assign(nBlocks, -1);
  std::vector<uint32_t> ahead;
  for (uint32_t b : grid.owning) {
    const BlockCoord& Y = grid.topology.coord(b);
    for (int d = 0; d < 8; ++d) {
      const BlockCoord X = offset(Y, d, +1);
      std::array<int, 8> h{};
      const int k = ranks.holders(X, h);
      const int counting = k > 1 ? ranks.counting(X) : me;
      for (int i = 0; i < k; ++i)
        if (const int r = h[size_t(i)]; r != me) sends.push_back({b, d, r, r == counting ? partBox(d) : ranks.reach(X, r, d)});
    }
    if (!sends.empty() && sends.back().block == b && slot_[b] < 0) {
      slot_[b] = int32_t(ahead.size());
      ahead.push_back(b);
    }
  }
  stored_.resize(ahead.size() * kPadNodes);
  storedExtra_.resize(ahead.size() * kPadNodes * size_t(channels_));
  tbb::parallel_for(size_t(0), ahead.size(), [&](size_t i) {
    scatterBlock(groups, grid, ahead[i], dt, stored_.data() + i * kPadNodes,
                 storedExtra_.data() + i * kPadNodes * size_t(channels_));
  });

  std::vector<std::vector<char>> out(static_cast<size_t>(n));
  for (const Send& s : sends) pack(s, grid, out[size_t(s.rank)]);
  lastBytes_ = 0;
  for (int r = 0; r < n; ++r) lastBytes_ += r == me ? 0 : out[size_t(r)].size();
  received_ = comm.exchange(out);
  indexReceived(grid);
}

void HaloExchange::pack(const Send& s, const SparseGrid& grid, std::vector<char>& o) const {
  const BlockCoord& Y = grid.topology.coord(s.block);
  Header h{Y.x, Y.y, Y.z, s.d, {}, {}, {}};
  for (int a = 0; a < 3; ++a) h.lo[a] = int8_t(s.box.lo[a]), h.hi[a] = int8_t(s.box.hi[a]);
  o.insert(o.end(), reinterpret_cast<const char*>(&h), reinterpret_cast<const char*>(&h) + sizeof(h));
  const Vec4* buf = stored(s.block);
  forEachPaddedRow(s.box, [&](int d, int pad, int, int len) {
    if (d != s.d) return;
    const char* p = reinterpret_cast<const char*>(buf + pad);
    o.insert(o.end(), p, p + size_t(len) * sizeof(Vec4));
  });
  if (!channels_) return;
  const float* ex = storedExtra(s.block);
  forEachPaddedRow(s.box, [&](int d, int pad, int, int len) {
    if (d != s.d) return;
    const char* p = reinterpret_cast<const char*>(ex + size_t(pad) * size_t(channels_));
    o.insert(o.end(), p, p + size_t(len) * size_t(channels_) * sizeof(float));
  });
}

void HaloExchange::indexReceived(const SparseGrid& grid) {
  for (auto& list : remote_) list.clear();
  BlockTopology::Lookup lookup(grid.topology);
  for (const std::vector<char>& in : received_)
    for (size_t pos = 0; pos < in.size();) {
      Header h;
      std::memcpy(&h, in.data() + pos, sizeof(h));
      pos += sizeof(h);
      const BlockCoord Y{h.x, h.y, h.z};
      const int32_t target = lookup.find(offset(Y, h.d, +1));
      if (target < 0) throw std::logic_error("halo rows for a block this rank does not hold");
      PadBox box;
      for (int a = 0; a < 3; ++a) box.lo[a] = h.lo[a], box.hi[a] = h.hi[a];
      const size_t nodes = size_t(boxNodes(box));
      remote_[size_t(blockColour(Y))].push_back({target, h.d, box, in.data() + pos, in.data() + pos + nodes * sizeof(Vec4)});
      pos += nodes * (sizeof(Vec4) + size_t(channels_) * sizeof(float));
    }
}

} // namespace talus
