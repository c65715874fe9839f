// HDF5 checkpoints: the full simulation state, written atomically (temporary file + rename), so a
// run killed at any moment leaves the previous checkpoint intact and readable.
#pragma once

#include "engine/simulation.h"

#include <functional>
#include <string>

namespace talus {

/// DIR/checkpoint.h5.
std::string checkpointPath(const std::string& dir);

/// Writes sim's state (see Simulation::save) and whatever `extra` adds (the run driver's clock
/// and its outputs' accumulated state).
void writeCheckpoint(const std::string& path, const Simulation& sim,
                     const std::function<void(StateArchive&)>& extra = {});

/// Restores a checkpoint into a simulation built from the same scene, then calls `extra`.
/// Throws std::runtime_error naming the file when it is missing, unreadable or does not match.
void readCheckpoint(const std::string& path, Simulation& sim,
                    const std::function<void(const StateArchive&)>& extra = {});

} // namespace talus
