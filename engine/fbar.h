// F-bar (de Souza Neto et al. 1996; in MPM, Coombs et al. 2018 and the ΔJ-bar of Zhao et al. 2023):
// a pass between the grid update and G2P that averages the step's volume change of the solids over
// the grid, so that a particle's deformation increment takes its deviatoric part from its own
// velocity gradient and its volumetric part from that average. An isochoric plastic flow (the
// Drucker–Prager return keeps volume) then no longer has to hold ∇·v = 0 at every particle, the
// over-constraint (volumetric locking) that stiffens flow on coarse grids.
#pragma once

#include "engine/material_group.h"
#include "engine/sparse_grid.h"

#include <array>
#include <vector>

namespace talus {

/// Scatters, for the particles of every group that averagesVolume() (when grid.channels.fbar is
/// set), m (ΔJ - 1) and m into the two channels from grid.channels.fbar, ΔJ = det(I + dt C) with
/// C gathered from the updated grid velocities; and for every group that averagesState(), m (J ΔJ
/// - 1) and m, its J after the step (cut at 1 + averagedStateMax()), into those from grid.channels.stateJ.
/// Colour by colour, per-block buffers: the same sums at any thread count.
void averageVolumeChange(const std::vector<MaterialGroup*>& groups, SparseGrid& grid, Real dt);

/// The mean of channel pair `channel` (grid.channels.fbar: ΔJ - 1; stateJ: J - 1) over the padded
/// neighbourhood of a block (`up`: it and its 7 upper neighbours), 0 where no particle reached a
/// node, in padIndex order (G2PBlock::meanVolumeChange), inside `box`.
void copyMeanVolumeChange(const SparseGrid& grid, int channel, const std::array<int32_t, 8>& up, Real* out,
                          const PadBox& box);

} // namespace talus
