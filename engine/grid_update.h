// Grid update: momentum to velocity, gravity, then boundary conditions on every active node.
#pragma once

#include "engine/boundary.h"
#include "engine/sparse_grid.h"

namespace talus {

struct GridUpdateParams {
  Real dt = 0;
  Vec3 gravity = Vec3::Zero();
  Real damping = 0; ///< velocity damping rate (1/s), see SimulationSettings::damping
  DomainBox domain;                  ///< local frame
  bool hasTerrain = false;
  BoundaryCondition terrain;
};

/// After this, node records hold (mass, velocity).
void updateGridVelocities(SparseGrid& grid, const GridUpdateParams& params);

} // namespace talus
