#include "engine/sdf.h"

#include "engine/block_topology.h"

#include <algorithm>
#include <limits>
#include <sstream>
#include <tbb/parallel_for.h>

namespace talus {

bool Sdf::sampleBlock(const BlockCoord& c, double dx, SdfBlock& out) const {
  bool any = false;
  for (int i = 0; i < kBlockDim; ++i)
    for (int j = 0; j < kBlockDim; ++j)
      for (int k = 0; k < kBlockDim; ++k) {
        const int n = blockNodeIndex(i, j, k);
        const Vec3d x((c.x * kBlockDim + i) * dx, (c.y * kBlockDim + j) * dx, (c.z * kBlockDim + k) * dx);
        const double phi = distance(x);
        const Vec3d g = normal(x, 0.25 * dx);
        out.phi[n] = float(phi);
        for (int d = 0; d < 3; ++d) out.normal[n][d] = float(g[d]);
        any |= phi <= 0;
      }
  return any;
}

Vec3d Sdf::normal(const Vec3d& x, double h) const {
  Vec3d g;
  for (int d = 0; d < 3; ++d) {
    Vec3d e = Vec3d::Zero();
    e[d] = h;
    g[d] = distance(x + e) - distance(x - e);
  }
  const double len = g.norm();
  return len > 1e-12 ? Vec3d(g / len) : Vec3d::Zero();
}

void Sdf::bounds(Vec3d& lo, Vec3d& hi) const {
  lo = Vec3d::Constant(-std::numeric_limits<double>::infinity());
  hi = Vec3d::Constant(std::numeric_limits<double>::infinity());
}

PlaneSdf::PlaneSdf(const Vec3d& point, const Vec3d& normal)
    : point_(point), normal_(normal.normalized()) {}


std::string PlaneSdf::describe() const {
  std::ostringstream s;
  s << "plane through (" << point_.transpose() << ") with normal (" << normal_.transpose() << ")";
  return s.str();
}

void SdfCache::attach(const BlockTopology& topo, std::vector<const SdfBlock*>& out) {
  const size_t n = topo.size();
  out.assign(n, nullptr);
  std::vector<uint32_t> missing;
  for (uint32_t b = 0; b < n; ++b) {
    auto it = slots_.find(blockKey(topo.coord(b)));
    if (it == slots_.end()) missing.push_back(b);
    else if (it->second >= 0) out[b] = blocks_[it->second].get();
  }
  if (focus_ && n > 0) { // the terrain this process still needs: around its active blocks
    BlockCoord lo = topo.coord(0), hi = lo;
    for (uint32_t b = 1; b < n; ++b) {
      const BlockCoord& c = topo.coord(b);
      lo = {std::min(lo.x, c.x), std::min(lo.y, c.y), std::min(lo.z, c.z)};
      hi = {std::max(hi.x, c.x), std::max(hi.y, c.y), std::max(hi.z, c.z)};
    }
    sdf_->focus(lo, hi, dx_);
  }
  if (missing.empty()) return;
  std::vector<std::unique_ptr<SdfBlock>> fresh(missing.size());
  tbb::parallel_for(size_t(0), missing.size(), [&](size_t i) {
    auto tb = std::make_unique<SdfBlock>();
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
