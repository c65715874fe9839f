#include "engine/particle_binning.h"

#include "engine/bspline.h"

#include <tbb/parallel_for.h>

namespace talus {

namespace {
constexpr size_t kChunk = 4096; // fixed chunking keeps results independent of thread count

size_t chunkCount(size_t n) { return (n + kChunk - 1) / kChunk; }
} // namespace

void binParticles(const std::vector<MaterialGroup*>& groups, SparseGrid& grid, ReorderScratch& scratch,
                  const Periodicity* periodic, const std::vector<ParticleOrder>* order) {
  const Real invDx = Real(1) / grid.dx;

  // 1. Owning blocks. Particles are mostly sorted already, so runs of equal blocks are long
  //    and each chunk contributes few coordinates. The runs (coordinate, length) are kept for
  //    step 2, which then needs no second pass over the particles.
  struct CoordRun {
    BlockCoord block;
    uint32_t count;
  };
  std::vector<BlockCoord> owning;
  std::vector<std::vector<std::vector<CoordRun>>> coordRuns(groups.size()); // [group][chunk]
  for (size_t gi = 0; gi < groups.size(); ++gi) {
    const auto& x = groups[gi]->particles.x;
    auto& runs = coordRuns[gi];
    runs.resize(chunkCount(x.size()));
    tbb::parallel_for(size_t(0), runs.size(), [&](size_t c) {
      const size_t end = std::min(x.size(), (c + 1) * kChunk);
      for (size_t p = c * kChunk; p < end; ++p) {
        const BlockCoord b = owningBlock(x[p], invDx);
        if (runs[c].empty() || b != runs[c].back().block) runs[c].push_back({b, 0});
        ++runs[c].back().count;
      }
    });
    for (const auto& chunk : runs)
      for (const CoordRun& r : chunk) owning.push_back(r.block);
  }
  if (periodic && periodic->any()) periodic->addImages(owning);
  grid.topology.rebuild(owning);
  const size_t nBlocks = grid.topology.size();

  // 2. Per group: block index per particle, stable counting sort, reorder if needed. Each chunk
  //    records its runs of equal blocks; the counts and each run's place in the sorted order come
  //    from one serial pass over the runs (few: particles are mostly sorted), so the per-particle
  //    work is parallel and the permutation is the serial counting sort's, at any thread count.
  struct Run {
    uint32_t block, count, to = 0; // `to`: the run's first index in the sorted order
  };
  std::vector<uint32_t> particleCount(nBlocks, 0);
  for (size_t gi = 0; gi < groups.size(); ++gi) {
    MaterialGroup* g = groups[gi];
    auto& x = g->particles.x;
    const size_t n = x.size();
    // Chunks in the order the sort is stable in: the array's, or the segments given for it.
    std::vector<std::pair<size_t, size_t>> chunks;
    auto segment = [&](size_t b, size_t e) {
      for (size_t c = b; c < e; c += kChunk) chunks.push_back({c, std::min(e, c + kChunk)});
    };
    const bool segments = order && !(*order)[gi].empty();
    if (segments)
      for (const auto& [b, e] : (*order)[gi]) segment(b, e);
    else
      segment(0, n);
    bool inPlace = true; // the chunks follow the array
    for (size_t c = 1; c < chunks.size(); ++c) inPlace = inPlace && chunks[c].first == chunks[c - 1].second;
    std::vector<std::vector<Run>> runs(chunks.size());
    tbb::parallel_for(size_t(0), runs.size(), [&](size_t c) {
      BlockTopology::Lookup lookup(grid.topology);
      if (!segments) { // the chunks of step 1: its runs, looked up
        for (const CoordRun& r : coordRuns[gi][c]) runs[c].push_back({uint32_t(lookup.find(r.block)), r.count});
        return;
      }
      const size_t end = chunks[c].second;
      BlockCoord last{INT32_MIN, 0, 0};
      uint32_t lastIndex = 0;
      for (size_t p = chunks[c].first; p < end; ++p) {
        const BlockCoord b = owningBlock(x[p], invDx);
        if (b != last) last = b, lastIndex = uint32_t(lookup.find(b));
        if (runs[c].empty() || runs[c].back().block != lastIndex) runs[c].push_back({lastIndex, 0});
        ++runs[c].back().count;
      }
    });

    auto& start = g->blockStart;
    start.assign(nBlocks + 1, 0);
    bool sorted = inPlace;
    uint32_t previous = 0;
    for (const auto& chunk : runs)
      for (const Run& r : chunk) {
        start[r.block + 1] += r.count;
        sorted = sorted && r.block >= previous;
        previous = r.block;
      }
    for (size_t b = 0; b < nBlocks; ++b) {
      particleCount[b] += start[b + 1];
      start[b + 1] += start[b];
    }
    if (!sorted) {
      std::vector<uint32_t> cursor(start.begin(), start.end() - 1);
      for (auto& chunk : runs)
        for (Run& r : chunk) r.to = cursor[r.block], cursor[r.block] += r.count;
      auto& perm = scratch.perm;
      perm.index.resize(n);
      // The permutation moves the runs whose place changes; the range they span is all a
      // reorder has to copy (most of an array where only part of a scene flows stays put).
      perm.begin = n, perm.end = 0;
      for (size_t c = 0; c < runs.size(); ++c) {
        size_t p = chunks[c].first;
        for (const Run& r : runs[c]) {
          if (r.to != p) perm.begin = std::min<size_t>(perm.begin, r.to), perm.end = std::max<size_t>(perm.end, r.to + r.count);
          p += r.count;
        }
      }
      perm.begin = std::min(perm.begin, perm.end);
      tbb::parallel_for(size_t(0), runs.size(), [&](size_t c) {
        uint32_t p = uint32_t(chunks[c].first);
        for (const Run& r : runs[c])
          for (uint32_t i = 0; i < r.count; ++i) perm.index[r.to + i] = p++;
      });
      g->particles.forEachArray([&](auto& a) { gatherInPlace(a, perm, scratch); });
      g->permuteState(perm, scratch);
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
  grid.extra.assign(nBlocks * kBlockNodes * size_t(grid.channels.count), 0.f);
}

} // namespace talus
