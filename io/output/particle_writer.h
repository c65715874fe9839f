// Particle snapshots in HDF5 (the format is documented in README.md, "Outputs").
#pragma once

#include "engine/communicator.h"
#include "engine/simulation.h"
#include "io/common/write_error.h"

#include <optional>
#include <string>
#include <vector>

namespace talus {

/// Writes /particles/position (N x 3 double, world coordinates), /particles/velocity (N x 3
/// float), /particles/material (N int32, index into material_names), /particles/mass (N float)
/// and file attributes `time` (s) and `material_names`. Written to a temporary file and
/// renamed, so a reader never sees a half-written snapshot. Throws WriteError naming `path`.
void writeParticlesH5(const std::string& path, const Simulation& sim, const std::vector<std::string>& materialNames);

/// The same file written by every process with its own particles (`local`), collectively: the
/// bytes are one process's at any rank count (io/output/particle_file_parts.h). Returns on rank 0
/// the first failure (nothing elsewhere).
std::optional<WriteError> writeParticlesH5(Communicator& comm, const std::string& path, const Simulation& local,
                                           const std::vector<std::string>& materialNames);

} // namespace talus
