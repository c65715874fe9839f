#include "engine/union_terrain.h"

#include <algorithm>
#include <limits>

namespace talus {

bool UnionTerrain::sampleBlock(const BlockCoord& c, double dx, TerrainBlock& out) const {
  bool any = false;
  TerrainBlock part;
  for (const auto& p : parts_) {
    if (!p->sampleBlock(c, dx, any ? part : out)) continue;
    if (any)
      for (int n = 0; n < kBlockNodes; ++n)
        if (part.phi[n] < out.phi[n]) {
          out.phi[n] = part.phi[n];
          std::copy(part.normal[n], part.normal[n] + 3, out.normal[n]);
        }
    any = true;
  }
  return any;
}

double UnionTerrain::distance(const Vec3d& x) const {
  double d = std::numeric_limits<double>::infinity();
  for (const auto& p : parts_) d = std::min(d, p->distance(x));
  return d;
}

std::string UnionTerrain::describe() const {
  std::string s = "union of";
  for (size_t i = 0; i < parts_.size(); ++i) s += (i ? "; " : " ") + parts_[i]->describe();
  return s;
}

bool FunctionTerrain::sampleBlock(const BlockCoord& c, double dx, TerrainBlock& out) const {
  bool any = false;
  const double h = 0.25 * dx;
  for (int i = 0; i < kBlockDim; ++i)
    for (int j = 0; j < kBlockDim; ++j)
      for (int k = 0; k < kBlockDim; ++k) {
        const int n = blockNodeIndex(i, j, k);
        const Vec3d x((c.x * kBlockDim + i) * dx, (c.y * kBlockDim + j) * dx, (c.z * kBlockDim + k) * dx);
        const double phi = sdf_(x);
        Vec3d g;
        for (int d = 0; d < 3; ++d) {
          Vec3d e = Vec3d::Zero();
          e[d] = h;
          g[d] = sdf_(x + e) - sdf_(x - e);
        }
        const double len = g.norm();
        g = len > 1e-12 ? Vec3d(g / len) : Vec3d::Zero();
        out.phi[n] = float(phi);
        for (int d = 0; d < 3; ++d) out.normal[n][d] = float(g[d]);
        any |= phi <= 0;
      }
  return any;
}

} // namespace talus
