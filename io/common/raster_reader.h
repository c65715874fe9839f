// Reading band 1 of a raster (a map GeoTIFF, an animation frame) as floats, through GDAL.
#pragma once

#include "io/common/raster_grid.h"

#include <string>
#include <vector>

namespace talus {

struct FloatRaster {
  RasterGrid grid;
  std::vector<float> values; ///< grid.index(c, r) order
  std::string timeSeconds;   ///< metadata TALUS_TIME_S (animation frames), or empty
};

/// Throws InputError naming `path` and saying it cannot read `what` ("this animation frame").
FloatRaster readFloatRaster(const std::string& path, const std::string& what);

} // namespace talus
