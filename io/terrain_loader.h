// Builds the terrain SDF a [terrain] section asks for.
#pragma once

#include "engine/config_table.h"
#include "engine/simulation.h"

#include <memory>

namespace talus {

/// `plane = { point = [...], normal = [...] }` or `sdf = "terrain.vdb"` (optionally `grid`).
/// Relative file paths are resolved against the scene file's directory.
std::shared_ptr<const TerrainSdf> loadTerrain(const ConfigTable& terrain, const SimulationSettings& settings);

/// `path` relative to the directory of `sceneFile` unless absolute.
std::string resolveScenePath(const std::string& sceneFile, const std::string& path);

} // namespace talus
