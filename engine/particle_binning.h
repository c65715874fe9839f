// Sort particles by the block that owns them and rebuild the active grid topology.
#pragma once

#include "engine/material_group.h"
#include "engine/periodic.h"
#include "engine/sparse_grid.h"

#include <vector>

namespace talus {

/// Rebuilds grid.topology from particle positions, stably sorts every group's particles by
/// owning block (physically reordering their arrays), fills each group's blockStart, the
/// grid's owning-block list and colour lists, and zeroes the node arrays.
/// With `periodic`, the images of blocks holding ghost nodes are made active too.
/// @param scratch  buffers kept between steps (the caller owns them; contents are not read)
/// With `order` (one entry per group, may be empty), a group's sort is stable in the order of
/// the listed [begin, end) segments of its arrays instead of the arrays' own (MPI migration
/// appends arrivals that belong before the rank's own particles: engine/domain_decomposition.h).
using ParticleOrder = std::vector<std::pair<size_t, size_t>>;
void binParticles(const std::vector<MaterialGroup*>& groups, SparseGrid& grid, ReorderScratch& scratch,
                  const Periodicity* periodic = nullptr, const std::vector<ParticleOrder>* order = nullptr);

} // namespace talus
