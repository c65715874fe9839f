// Per-material mass and total momentum on grid nodes, scattered from the particles at frame time.
//
// The simulation grid only holds total mass and velocity, and only after a step (frame 0 has no
// grid data), so volume frames scatter their own: the engine's quadratic B-spline weights on the
// same node lattice, 8^3 blocks at the same origins, one entry per material. Because the weights
// are a partition of unity, summed over nodes they reproduce every material's mass exactly.
#pragma once

#include "engine/simulation.h"

#include <vector>

namespace talus {

struct NodeFields {
  double dx = 1;
  int materials = 0;              ///< in sim.groups() order
  std::vector<BlockCoord> blocks; ///< blocks holding any mass, in a deterministic order
  std::vector<float> mass;        ///< [block][material][blockNodeIndex] (kg)
  std::vector<float> momentum;    ///< [block][blockNodeIndex][3] (kg m/s), all materials

  float* blockMass(size_t b, int m) { return mass.data() + (b * size_t(materials) + size_t(m)) * kBlockNodes; }
  const float* blockMass(size_t b, int m) const {
    return mass.data() + (b * size_t(materials) + size_t(m)) * kBlockNodes;
  }
  float* blockMomentum(size_t b) { return momentum.data() + b * kBlockNodes * 3; }
  const float* blockMomentum(size_t b) const { return momentum.data() + b * kBlockNodes * 3; }
};

/// Node (i, j, k) of block c sits at (8 c + (i, j, k)) dx in the local frame.
NodeFields scatterNodeFields(const Simulation& sim);

} // namespace talus
