// Particle-to-grid scatter (MLS-MPM form of APIC), race-free by 8-colour block passes.
#pragma once

#include "engine/material_group.h"
#include "engine/sparse_grid.h"

#include <vector>

namespace talus {

/// Adds mass and momentum (including the stress impulse -dt V tau D^-1 (x_i - x_p)) of every
/// particle to grid.nodes. Blocks of one colour are two blocks apart, so their 2x2x2-block
/// footprints never overlap: no atomics, and every node sums its contributions in the same
/// order at any thread count (bit-identical results).
void particlesToGrid(const std::vector<MaterialGroup*>& groups, SparseGrid& grid, Real dt);

} // namespace talus
