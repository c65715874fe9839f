// Per-material mass and total momentum on grid nodes, scattered from the particles at frame time.
//
// The simulation grid only holds total mass and velocity, and only after a step (frame 0 has no
// grid data), so volume frames scatter their own: the engine's quadratic B-spline weights on the
// same node lattice, 8^3 blocks at the same origins, one entry per material. Because the weights
// are a partition of unity, summed over nodes they reproduce every material's mass.
//
// The sums are fixed-point: each particle's share of a node is rounded to a multiple of its
// channel's unit (a power of two, from exact maxima over every particle) and added as an integer.
// Integer sums do not depend on their order, so the processes of a run on ranks each scatter
// their own particles and rank 0 adds their blocks: the same bits as one process's, without
// gathering the particles (docs/scaling.md, "Frames").
#pragma once

#include "engine/communicator.h"
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

/// Fixed-point node sums of one process's particles (or, after gatherNodeSums, of all of them).
struct NodeSums {
  double dx = 1;
  int materials = 0;
  std::vector<double> unit;       ///< per channel: the materials' masses (kg), then momentum (kg m/s)
  std::vector<BlockCoord> blocks; ///< sorted by (x, y, z)
  std::vector<int64_t> values;    ///< [block][channel][blockNodeIndex], channel = material or 3 momenta
  int channels() const { return materials + 3; }
};

/// Collective (the units come from every process's maxima): `local`'s particles scattered into
/// the blocks their stencils reach, sorted.
NodeSums scatterNodeSums(Communicator& comm, const Simulation& local);
/// Collective: every process's sums added into rank 0's (one process's part at a time, so rank 0
/// holds its own and one other's besides the total); the others' are left as they were.
void gatherNodeSums(Communicator& comm, NodeSums& sums);
/// The sums as floats, without the blocks that received no mass.
NodeFields nodeFields(const NodeSums& sums);

/// Node (i, j, k) of block c sits at (8 c + (i, j, k)) dx in the local frame. One process's
/// scatterNodeSums and nodeFields.
NodeFields scatterNodeFields(const Simulation& sim);

} // namespace talus
