// DEM -> narrow-band OpenVDB level set (a .vdb file that VdbLevelSet reads).
//
// Voxel (i, j, k) has its centre at origin + (i, j, k) dx in world coordinates, so a level set
// built with the simulation's dx and origin has its voxels exactly on the grid nodes and
// VdbLevelSet's trilinear sampling returns the voxel values unchanged.
#pragma once

#include "engine/types.h"
#include "io/terrain/dem_raster.h"

#include <limits>
#include <string>

namespace talus {

struct LevelSetBuildOptions {
  double dx = 1;                 ///< voxel size (m)
  Vec3d origin = Vec3d::Zero();  ///< world position of voxel (0, 0, 0)'s centre
  int band = 3;                  ///< half width in voxels: voxels with |phi| < band dx are active
  /// Columns whose centres lie in [xmin, xmax] x [ymin, ymax] (world) are built; beyond the
  /// raster the surface continues at the height of its outermost cell centres.
  double xmin = 0, ymin = 0, xmax = 0, ymax = 0;
  /// The level set is inside (negative) below the band down to at least this world z; NaN:
  /// 128 voxels below the lowest point of the surface.
  double zmin = std::numeric_limits<double>::quiet_NaN();
  /// true: distance to the closest point of the bilinear surface (a projection iterated from the
  /// vertical foot point; exact for planes and smooth terrain), except for the two voxels of
  /// each column that bracket the surface, which hold the slope-corrected vertical difference so
  /// the zero crossing of every column is exactly at the surface height. false: the
  /// slope-corrected vertical difference (z - h) / sqrt(1 + |grad h|^2) everywhere, exact for
  /// planes alone (kept for comparison).
  bool closestPoint = true;
  // Metadata written into the grid.
  std::string sourcePath;
  double smoothRadius = 0;
};

struct LevelSetBuildStats {
  size_t activeVoxels = 0;
  size_t leaves = 0;
  size_t columns = 0;        ///< voxel columns built
  double buildSeconds = 0;   ///< distance evaluation and tree construction
  double writeSeconds = 0;
  size_t fileBytes = 0;
};

/// Builds the level set (FloatGrid "terrain", class level set, negative below ground, true
/// distances within the band, +-band dx beyond) and writes it to `path` (atomically).
/// Metadata: crs_wkt, origin, dx, band_voxels, source, smooth_radius, distance_method.
LevelSetBuildStats buildDemLevelSet(const HeightField& surface, const LevelSetBuildOptions& options,
                                    const std::string& path);

} // namespace talus
