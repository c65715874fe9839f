#include "engine/particle_binning.h"

#include "engine/bspline.h"

#include <tbb/parallel_for.h>

namespace talus {

namespace {
constexpr size_t kChunk = 4096; // fixed chunking keeps results independent of thread count

size_t chunkCount(size_t n) { return (n + kChunk - 1) / kChunk; }
} // namespace

void binParticles(const std::vector<MaterialGroup*>& groups, SparseGrid& grid, const Periodicity* periodic) {
  const Real invDx = Real(1) / grid.dx;

  // 1. Owning blocks. Particles are mostly sorted already, so runs of equal blocks are long
  //    and each chunk contributes few coordinates.
  std::vector<BlockCoord> owning;
  for (MaterialGroup* g : groups) {
    const auto& x = g->particles.x;
    std::vector<std::vector<BlockCoord>> runs(chunkCount(x.size()));
    tbb::parallel_for(size_t(0), runs.size(), [&](size_t c) {
      const size_t end = std::min(x.size(), (c + 1) * kChunk);
      BlockCoord last{INT32_MIN, 0, 0};
      for (size_t p = c * kChunk; p < end; ++p) {
        const BlockCoord b = owningBlock(x[p], invDx);
        if (b != last) runs[c].push_back(b), last = b;
      }
    });
    for (const auto& r : runs) owning.insert(owning.end(), r.begin(), r.end());
  }
  if (periodic && periodic->any()) periodic->addImages(owning);
  grid.topology.rebuild(owning);
  const size_t nBlocks = grid.topology.size();

  // 2. Per group: block index per particle, stable counting sort, reorder if needed.
  std::vector<uint32_t> particleCount(nBlocks, 0);
  for (MaterialGroup* g : groups) {
    auto& x = g->particles.x;
    const size_t n = x.size();
    std::vector<uint32_t> blockOf(n);
    std::vector<uint8_t> sortedChunk(chunkCount(n), 1);
    tbb::parallel_for(size_t(0), sortedChunk.size(), [&](size_t c) {
      BlockTopology::Lookup lookup(grid.topology);
      const size_t end = std::min(n, (c + 1) * kChunk);
      BlockCoord last{INT32_MIN, 0, 0};
      int32_t lastIndex = -1;
      for (size_t p = c * kChunk; p < end; ++p) {
        const BlockCoord b = owningBlock(x[p], invDx);
        if (b != last) last = b, lastIndex = lookup.find(b);
        blockOf[p] = uint32_t(lastIndex);
        if (p > c * kChunk && blockOf[p] < blockOf[p - 1]) sortedChunk[c] = 0;
      }
    });
    bool sorted = true;
    for (size_t c = 0; c < sortedChunk.size(); ++c) {
      if (!sortedChunk[c]) sorted = false;
      if (c > 0 && blockOf[c * kChunk] < blockOf[c * kChunk - 1]) sorted = false;
    }

    auto& start = g->blockStart;
    start.assign(nBlocks + 1, 0);
    for (size_t p = 0; p < n; ++p) ++start[blockOf[p] + 1];
    for (size_t b = 0; b < nBlocks; ++b) {
      particleCount[b] += start[b + 1];
      start[b + 1] += start[b];
    }
    if (!sorted) {
      std::vector<uint32_t> perm(n), cursor(start.begin(), start.end() - 1);
      for (size_t p = 0; p < n; ++p) perm[cursor[blockOf[p]]++] = uint32_t(p);
      g->particles.forEachArray([&](auto& a) { gatherInPlace(a, perm); });
      g->permuteState(perm);
    }
  }

  // 3. Owning blocks, colour lists, zeroed node arrays.
  grid.owning.clear();
  for (auto& c : grid.colours) c.clear();
  for (uint32_t b = 0; b < nBlocks; ++b)
    if (particleCount[b]) {
      grid.owning.push_back(b);
      grid.colours[blockColour(grid.topology.coord(b))].push_back(b);
    }
  grid.nodes.resize(nBlocks * kBlockNodes);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, grid.nodes.size(), 1 << 14), [&](const auto& r) {
    std::fill(grid.nodes.begin() + r.begin(), grid.nodes.begin() + r.end(), Vec4::Zero());
  });
  grid.extra.assign(nBlocks * kBlockNodes * size_t(grid.extraChannels), 0.f);
}

} // namespace talus
