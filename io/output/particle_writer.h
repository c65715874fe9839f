// Particle snapshots in HDF5 (the format is documented in README.md, "Outputs").
#pragma once

#include "engine/simulation.h"

#include <string>
#include <vector>

namespace talus {

/// Writes /particles/position (N x 3 double, world coordinates), /particles/velocity (N x 3
/// float), /particles/material (N int32, index into material_names), /particles/mass (N float)
/// and file attributes `time` (s) and `material_names`. Written to a temporary file and
/// renamed, so a reader never sees a half-written snapshot.
void writeParticlesH5(const std::string& path, const Simulation& sim, const std::vector<std::string>& materialNames);

} // namespace talus
