// The MPI ranks' ranges of blocks (engine/domain_decomposition.h), in one process: the order they
// are cut from must be BlockTopology's own, or the ranks' arrays stop being one process's.
#include "engine/block_topology.h"
#include "engine/domain_decomposition.h"

#include <algorithm>
#include <gtest/gtest.h>
#include <random>

using namespace talus;

namespace {
/// A communicator of `n` ranks seen from `rank`, for balance() and owner() (no messages).
class FakeRanks final : public Communicator {
public:
  FakeRanks(int rank, int n) : rank_(rank), n_(n) {}
  int rank() const override { return rank_; }
  int size() const override { return n_; }
  double maxOf(double v) override { return v; }
  double minOf(double v) override { return v; }
  uint64_t sumOf(uint64_t v) override { return v; }
  void sum(double*, size_t) override {}
  void minimum(double*, size_t) override {}
  std::vector<char> allGather(const std::vector<char>& m, std::vector<size_t>& c) override { return c = {m.size()}, m; }
  std::vector<char> gather(const std::vector<char>& m, std::vector<size_t>& c) override { return c = {m.size()}, m; }
  std::vector<std::vector<char>> exchange(std::vector<std::vector<char>>& s) override { return s; }
private:
  int rank_, n_;
};
} // namespace

TEST(DomainDecomposition, TreeOrderIsTheTopologysBlockOrderAcrossEveryLevelOfTheTree) {
  // Coordinates spread over leaf (8), internal (128) and root (4096) boundaries, negative too.
  std::mt19937 rng(7);
  std::uniform_int_distribution<int32_t> wide(-9000, 9000), narrow(-20, 140);
  std::vector<BlockCoord> coords;
  for (int i = 0; i < 4000; ++i) coords.push_back({wide(rng), narrow(rng), wide(rng)});
  for (int i = 0; i < 4000; ++i) coords.push_back({narrow(rng), narrow(rng), narrow(rng)});
  BlockTopology topo;
  topo.rebuild(coords); // adds the +1 closure: more coordinates still
  ASSERT_GT(topo.size(), 8000u);
  size_t checked = 0;
  for (uint32_t b = 1; b < topo.size(); ++b, ++checked) {
    ASSERT_TRUE(treeOrderLess(topo.coord(b - 1), topo.coord(b))) << "blocks " << b - 1 << " and " << b;
    ASSERT_FALSE(treeOrderLess(topo.coord(b), topo.coord(b - 1)));
  }
  EXPECT_GT(checked, 8000u);
}

TEST(DomainDecomposition, RangesHoldEqualParticleCountsAndCoverEveryBlockOnce) {
  std::vector<std::pair<BlockCoord, uint64_t>> blocks;
  for (int x = 0; x < 20; ++x)
    for (int y = 0; y < 10; ++y) blocks.push_back({{x, y, 0}, uint64_t(100 + 37 * ((x * 7 + y) % 5))});
  uint64_t total = 0;
  for (const auto& b : blocks) total += b.second;
  for (int n : {2, 3, 4, 7}) {
    DomainDecomposition dd(std::make_shared<FakeRanks>(0, n), 0.1);
    dd.balance(blocks);
    std::vector<uint64_t> load(size_t(n), 0);
    std::vector<std::pair<BlockCoord, uint64_t>> sorted = blocks;
    std::sort(sorted.begin(), sorted.end(), [](const auto& a, const auto& b) { return treeOrderLess(a.first, b.first); });
    int last = 0;
    for (const auto& [c, count] : sorted) {
      const int r = dd.owner(c);
      ASSERT_GE(r, last) << "ranges must be contiguous in tree order";
      last = r;
      load[size_t(r)] += count;
    }
    // Each rank within one block's count (at most 248 particles here) of its share.
    for (int r = 0; r < n; ++r) EXPECT_NEAR(double(load[size_t(r)]), double(total) / n, 248.0) << n << " ranks, rank " << r;
  }
}

TEST(DomainDecomposition, MoreRanksThanBlocksLeavesSomeRanksEmpty) {
  DomainDecomposition dd(std::make_shared<FakeRanks>(0, 4), 0.1);
  dd.balance({{{0, 0, 0}, 10}, {{1, 0, 0}, 10}});
  EXPECT_EQ(dd.owner({0, 0, 0}), 0);
  EXPECT_EQ(dd.owner({1, 0, 0}), 2);
  // Ranks 1 and 3 hold nothing; blocks beyond the last one belong to the last rank with a range.
  EXPECT_EQ(dd.owner({5, 5, 5}), 2);
}

TEST(DomainDecomposition, SharesSizeTheRanges) {
  // Rank 0 writes the outputs under talus run and may be given a smaller share, or none.
  std::vector<std::pair<BlockCoord, uint64_t>> blocks;
  for (int x = 0; x < 40; ++x) blocks.push_back({{x, 0, 0}, 100});
  for (const std::vector<double>& shares : {std::vector<double>{0.1, 0.3, 0.6}, std::vector<double>{0, 0.5, 0.5}}) {
    DomainDecomposition dd(std::make_shared<FakeRanks>(0, 3), 0.1);
    dd.setShares(shares);
    dd.balance(blocks);
    std::vector<double> load(3, 0);
    for (const auto& [c, count] : blocks) load[size_t(dd.owner(c))] += double(count);
    // Within one block (100 particles) of each share of the 4000.
    for (int r = 0; r < 3; ++r) EXPECT_NEAR(load[size_t(r)], shares[size_t(r)] * 4000, 100.0) << "rank " << r;
  }
  DomainDecomposition dd(std::make_shared<FakeRanks>(0, 3), 0.1);
  EXPECT_THROW(dd.setShares({0.5, 0.5}), std::invalid_argument);
}
