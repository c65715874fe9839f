// HDF5 checkpoints: the full simulation state, written atomically (temporary file + rename), so a
// run killed at any moment leaves the previous checkpoint intact and readable.
#pragma once

#include "engine/simulation.h"

#include <string>

namespace talus {

/// DIR/checkpoint.h5.
std::string checkpointPath(const std::string& dir);

/// Writes sim's state (see Simulation::save) plus `frame`, the index of the next output frame.
void writeCheckpoint(const std::string& path, const Simulation& sim, int nextFrame);

/// Restores a checkpoint into a simulation built from the same scene; returns the next frame.
/// Throws std::runtime_error naming the file when it is missing, unreadable or does not match.
int readCheckpoint(const std::string& path, Simulation& sim);

} // namespace talus
