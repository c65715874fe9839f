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

/// Nodes in part d of a padded buffer (the block itself: 8^3; a face: 2 x 8 x 8; ...).
int partNodes(int d) {
  return ((d >> 2) ? 2 : kBlockDim) * (((d >> 1) & 1) ? 2 : kBlockDim) * ((d & 1) ? 2 : kBlockDim);
}

struct Header {
  int32_t x, y, z, d;
};

} // namespace

void HaloExchange::exchange(const std::vector<MaterialGroup*>& groups, SparseGrid& grid, Real dt,
                            DomainDecomposition& dd) {
  Communicator& comm = dd.comm();
  const int me = comm.rank(), n = comm.size();
  const size_t nBlocks = grid.blockCount();
  channels_ = std::max(grid.channels.count, 0);

  // 1. The owning blocks within one block of ours, with their ranks. Ranges say which rank owns
  // a coordinate (dd.owner), but only that rank knows whether the block holds particles: each
  // rank tells its owning blocks to the ranks owning one of their 26 neighbours. That is every
  // block holders() asks about (X - {0,1}^3 for X within +1 of our blocks), and no more.
  std::vector<std::vector<char>> tell(static_cast<size_t>(n));
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
  const std::vector<std::vector<char>> heard = comm.exchange(tell);
  std::unordered_map<uint64_t, int> rankOf;
  rankOf.reserve(grid.owning.size() * 2);
  for (uint32_t b : grid.owning) rankOf.emplace(blockKey(grid.topology.coord(b)), me);
  for (int r = 0; r < n; ++r)
    for (size_t at = 0; at + sizeof(BlockCoord) <= heard[size_t(r)].size(); at += sizeof(BlockCoord)) {
      BlockCoord c;
      std::memcpy(&c, heard[size_t(r)].data() + at, sizeof(c));
      rankOf.emplace(blockKey(c), r);
    }
  // The ranks holding block X: those owning one of X - {0,1}^3.
  auto holders = [&](const BlockCoord& X, std::array<int, 8>& out) {
    int k = 0;
    for (int e = 0; e < 8; ++e) {
      const auto it = rankOf.find(blockKey(offset(X, e, -1)));
      if (it == rankOf.end()) continue;
      bool seen = false;
      for (int i = 0; i < k; ++i) seen |= out[size_t(i)] == it->second;
      if (!seen) out[size_t(k++)] = it->second;
    }
    return k;
  };

  // 2. Loads are counted by the lowest rank holding a block.
  counted_.assign(nBlocks, 0);
  for (size_t b = 0; b < nBlocks; ++b) {
    std::array<int, 8> h{};
    const int k = holders(grid.topology.coord(uint32_t(b)), h);
    int lowest = me;
    for (int i = 0; i < k; ++i) lowest = std::min(lowest, h[size_t(i)]);
    counted_[b] = lowest == me;
  }

  // 3. Owning blocks whose parts other ranks hold: (block, part, rank).
  struct Send {
    uint32_t block;
    int d, rank;
  };
  std::vector<Send> sends;
  slot_.assign(nBlocks, -1);
  std::vector<uint32_t> ahead;
  for (uint32_t b : grid.owning) {
    const BlockCoord& Y = grid.topology.coord(b);
    for (int d = 0; d < 8; ++d) {
      std::array<int, 8> h{};
      const int k = holders(offset(Y, d, +1), h);
      for (int i = 0; i < k; ++i)
        if (h[size_t(i)] != me) sends.push_back({b, d, h[size_t(i)]});
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

  // 4. Pack, exchange, and index the received rows by the sender's colour.
  std::vector<std::vector<char>> out(static_cast<size_t>(n));
  for (const Send& s : sends) {
    const BlockCoord& Y = grid.topology.coord(s.block);
    auto& o = out[size_t(s.rank)];
    const Header h{Y.x, Y.y, Y.z, s.d};
    o.insert(o.end(), reinterpret_cast<const char*>(&h), reinterpret_cast<const char*>(&h) + sizeof(h));
    const Vec4* buf = stored(s.block);
    const float* ex = channels_ ? storedExtra(s.block) : nullptr;
    forEachPaddedRow([&](int d, int pad, int, int len) {
      if (d != s.d) return;
      const char* p = reinterpret_cast<const char*>(buf + pad);
      o.insert(o.end(), p, p + size_t(len) * sizeof(Vec4));
    });
    if (ex)
      forEachPaddedRow([&](int d, int pad, int, int len) {
        if (d != s.d) return;
        const char* p = reinterpret_cast<const char*>(ex + size_t(pad) * size_t(channels_));
        o.insert(o.end(), p, p + size_t(len) * size_t(channels_) * sizeof(float));
      });
  }
  lastBytes_ = 0;
  for (int r = 0; r < n; ++r) lastBytes_ += r == me ? 0 : out[size_t(r)].size();
  received_ = comm.exchange(out);
  for (auto& list : remote_) list.clear();
  BlockTopology::Lookup lookup(grid.topology);
  for (int r = 0; r < n; ++r) {
    const std::vector<char>& in = received_[size_t(r)];
    for (size_t pos = 0; pos < in.size();) {
      Header h;
      std::memcpy(&h, in.data() + pos, sizeof(h));
      pos += sizeof(h);
      const BlockCoord Y{h.x, h.y, h.z};
      const int32_t target = lookup.find(offset(Y, h.d, +1));
      if (target < 0) throw std::logic_error("halo rows for a block this rank does not hold");
      const size_t nodes = size_t(partNodes(h.d));
      RemoteRows rows{target, h.d, in.data() + pos, in.data() + pos + nodes * sizeof(Vec4)};
      pos += nodes * (sizeof(Vec4) + size_t(channels_) * sizeof(float));
      remote_[size_t(blockColour(Y))].push_back(rows);
    }
  }
}

} // namespace talus
