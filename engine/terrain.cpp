#include "engine/terrain.h"

#include "engine/block_topology.h"

#include <sstream>
#include <tbb/parallel_for.h>

namespace talus {

PlaneTerrain::PlaneTerrain(const Vec3d& point, const Vec3d& normal)
    : point_(point), normal_(normal.normalized()) {}

bool PlaneTerrain::sampleBlock(const BlockCoord& c, double dx, TerrainBlock& out) const {
  bool any = false;
  for (int i = 0; i < kBlockDim; ++i)
    for (int j = 0; j < kBlockDim; ++j)
      for (int k = 0; k < kBlockDim; ++k) {
        const int n = blockNodeIndex(i, j, k);
        const Vec3d x((c.x * kBlockDim + i) * dx, (c.y * kBlockDim + j) * dx, (c.z * kBlockDim + k) * dx);
        const double phi = distance(x);
        out.phi[n] = float(phi);
        for (int d = 0; d < 3; ++d) out.normal[n][d] = float(normal_[d]);
        any |= phi <= 0;
      }
  return any;
}

std::string PlaneTerrain::describe() const {
  std::ostringstream s;
  s << "plane through (" << point_.transpose() << ") with normal (" << normal_.transpose() << ")";
  return s.str();
}

namespace {
uint64_t blockKey(const BlockCoord& c) {
  return (uint64_t(uint32_t(c.x) & 0x1fffff) << 42) | (uint64_t(uint32_t(c.y) & 0x1fffff) << 21) |
         uint64_t(uint32_t(c.z) & 0x1fffff);
}
} // namespace

void TerrainCache::attach(const BlockTopology& topo, std::vector<const TerrainBlock*>& out) {
  const size_t n = topo.size();
  out.assign(n, nullptr);
  std::vector<uint32_t> missing;
  for (uint32_t b = 0; b < n; ++b) {
    auto it = slots_.find(blockKey(topo.coord(b)));
    if (it == slots_.end()) missing.push_back(b);
    else if (it->second >= 0) out[b] = blocks_[it->second].get();
  }
  if (missing.empty()) return;
  std::vector<std::unique_ptr<TerrainBlock>> fresh(missing.size());
  tbb::parallel_for(size_t(0), missing.size(), [&](size_t i) {
    auto tb = std::make_unique<TerrainBlock>();
    if (sdf_->sampleBlock(topo.coord(missing[i]), dx_, *tb)) fresh[i] = std::move(tb);
  });
  for (size_t i = 0; i < missing.size(); ++i) {
    int32_t slot = -1;
    if (fresh[i]) {
      slot = int32_t(blocks_.size());
      out[missing[i]] = fresh[i].get();
      blocks_.push_back(std::move(fresh[i]));
    }
    slots_[blockKey(topo.coord(missing[i]))] = slot;
  }
}

} // namespace talus
