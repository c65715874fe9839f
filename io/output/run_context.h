// What outputs need to know about the run besides their own settings: the grid spacing and
// times, where the world frame sits, the DEM maps are laid on, and the material names.
#pragma once

#include "engine/types.h"
#include "io/common/raster_grid.h"

#include <memory>
#include <string>
#include <vector>

namespace talus {

struct RunContext {
  double dx = 1;
  double endTime = 1;
  double particleSpacing = 1;                    ///< dx / cbrt(particles per cell) (m)
  Vec3d origin = Vec3d::Zero();                  ///< world position of the local frame
  Vec3d domainMin = Vec3d::Zero(), domainMax = Vec3d::Ones(); ///< local frame
  std::shared_ptr<const DemRaster> dem;          ///< the ground as simulated, or null
  std::string crsWkt;                            ///< the DEM's CRS, else the scene's [output] crs
  std::vector<std::string> materialNames;
  std::vector<std::string> materialModels; ///< per material, its model's name ("water", ...)
  std::string sceneKeys; ///< every scene key after overrides, "dotted.key = value" lines (ConfigTable::keyLines)
};

} // namespace talus
