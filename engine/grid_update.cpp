#include "engine/grid_update.h"

#include "engine/terrain.h"

#include <cmath>
#include <tbb/parallel_for.h>

namespace talus {

void updateGridVelocities(SparseGrid& grid, const GridUpdateParams& prm) {
  const double dx = grid.dx;
  // Node index thresholds of the walls: node i is on or beyond the low face when i <= lo.
  int lo[3], hi[3];
  for (int d = 0; d < 3; ++d) {
    lo[d] = int(std::floor(prm.domain.min[d] / dx + 1e-6));
    hi[d] = int(std::ceil(prm.domain.max[d] / dx - 1e-6));
  }
  const bool walls = prm.domain.walls.type != BoundaryType::Open;
  const Vec3 dtg = prm.dt * prm.gravity;
  const Real keep = Real(1) / (Real(1) + prm.damping * prm.dt);

  tbb::parallel_for(tbb::blocked_range<size_t>(0, grid.blockCount(), 16), [&](const auto& r) {
    for (size_t b = r.begin(); b != r.end(); ++b) {
      Vec4* nodes = grid.block(uint32_t(b));
      const BlockCoord& c = grid.topology.coord(uint32_t(b));
      const int o[3] = {c.x * kBlockDim, c.y * kBlockDim, c.z * kBlockDim};
      bool nearWall = false;
      for (int d = 0; d < 3; ++d) nearWall |= o[d] <= lo[d] || o[d] + kBlockDim - 1 >= hi[d];
      nearWall &= walls;
      const TerrainBlock* ground = prm.hasTerrain ? grid.terrain[b] : nullptr;

      for (int n = 0; n < kBlockNodes; ++n) {
        Vec4& node = nodes[n];
        if (node[0] <= Real(0)) {
          node.tail<3>().setZero();
          continue;
        }
        Vec3 v = (node.tail<3>() / node[0] + dtg) * keep;
        if (ground && ground->phi[n] <= 0.f) {
          const Vec3 nrm(Real(ground->normal[n][0]), Real(ground->normal[n][1]), Real(ground->normal[n][2]));
          // Deep inside a narrow band the SDF is flat and has no normal: hold the node still.
          v = nrm.squaredNorm() > Real(0.25) ? boundaryVelocity(v, nrm, prm.terrain) : Vec3::Zero();
        }
        if (nearWall) {
          const int idx[3] = {o[0] + (n >> 6), o[1] + ((n >> 3) & 7), o[2] + (n & 7)};
          for (int d = 0; d < 3; ++d) {
            if (idx[d] <= lo[d]) v = boundaryVelocity(v, Vec3::Unit(d), prm.domain.walls);
            if (idx[d] >= hi[d]) v = boundaryVelocity(v, -Vec3::Unit(d), prm.domain.walls);
          }
        }
        node.tail<3>() = v;
      }
    }
  });
}

} // namespace talus
