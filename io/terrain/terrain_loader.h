// Builds the terrain SDF a [terrain] section asks for.
#pragma once

#include "io/config/config_table.h"
#include "engine/simulation.h"
#include "io/terrain/dem_level_set.h"
#include "io/common/raster_grid.h"

#include <memory>
#include <string>
#include <vector>

namespace talus {

/// `plane = { point = [...], normal = [...] }` or `sdf = "terrain.vdb"` (optionally `grid`).
/// Relative file paths are resolved against the scene file's directory.
std::shared_ptr<const Sdf> loadTerrain(const ConfigTable& terrain, const SimulationSettings& settings);

/// `path` relative to the directory of `sceneFile` unless absolute.
std::string resolveScenePath(const std::string& sceneFile, const std::string& path);

/// True when the section describes a height field (`dem = ...` or `synthetic = {...}`).
bool isDemTerrain(const ConfigTable& terrain);

/// A height-field terrain as read: `dem` (a file) or `synthetic` (a generated kind), with
/// `fill_nodata`, `crs` and `smooth_radius` applied.
struct DemTerrainInput {
  std::shared_ptr<DemRaster> raw;      ///< as read (no-data filled), before smoothing
  std::shared_ptr<DemRaster> smoothed; ///< raw after Gaussian smoothing (== raw when R = 0)
  double smoothRadius = 0;
  size_t filledCells = 0;
  std::string description;             ///< for messages: file, size, cell, CRS
};
DemTerrainInput readDemTerrain(const ConfigTable& terrain);

/// Where built level sets are kept: $TALUS_CACHE_DIR, else $XDG_CACHE_HOME/talus/terrain, else
/// ~/.cache/talus/terrain (created on demand; the system temp dir when none can be created).
std::string terrainCacheDir();

struct CachedLevelSet {
  std::shared_ptr<const Sdf> sdf;
  std::string path;
  bool reused = false;
  LevelSetBuildStats stats;  ///< zero when reused
  double loadSeconds = 0;
};

/// The level set of `ground` for these options, from the cache when an identical one (same
/// heights, grid, CRS and options: a hash of all of them names the file) was built before,
/// else built and stored there. `origin` is the simulation's local origin (= options.origin).
CachedLevelSet cachedDemLevelSet(const DemRaster& ground, const LevelSetBuildOptions& options);

} // namespace talus
