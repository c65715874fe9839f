// Particle-to-grid scatter (MLS-MPM form of APIC), race-free by 8-colour block passes.
#pragma once

#include "engine/material_group.h"
#include "engine/padded_block.h"
#include "engine/sparse_grid.h"

#include <vector>

namespace talus {

class HaloExchange;

/// Adds mass and momentum (including the stress impulse -dt V tau D^-1 (x_i - x_p)) of every
/// particle to grid.nodes. Blocks of one colour are two blocks apart, so their 2x2x2-block
/// footprints never overlap: no atomics, and every node sums its contributions in the same
/// order at any thread count (bit-identical results).
/// With `halo` (MPI ranks), the blocks it scattered ahead are flushed from its buffers and the
/// rows other ranks sent are added in the colour pass of the block that sent them: every node
/// sums the same contributions in the same order as one process does.
void particlesToGrid(const std::vector<MaterialGroup*>& groups, SparseGrid& grid, Real dt,
                     const HaloExchange* halo = nullptr);

/// The padded nodes the particles of owning block b reach (their stencils' bounding box), or all
/// of them when the block holds more particles than that.
PadBox reachedNodes(const std::vector<MaterialGroup*>& groups, const SparseGrid& grid, uint32_t b);

/// Scatters the particles of owning block b into its padded buffer `buf` (kPadNodes) and, when the
/// grid has extra channels, `extra` (kPadNodes * channels). Both are zeroed here inside `box`, which
/// must hold reachedNodes(b); outside it they are left as they were.
void scatterBlock(const std::vector<MaterialGroup*>& groups, const SparseGrid& grid, uint32_t b, Real dt,
                  Vec4* buf, float* extra, const PadBox& box = PadBox{});

} // namespace talus
