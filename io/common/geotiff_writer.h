// Single-band Float32 GeoTIFFs through GDAL, georeferenced on a RasterGrid (north-up).
#pragma once

#include "io/common/raster_grid.h"

#include <string>
#include <utility>
#include <vector>

namespace talus {

struct GeoTiffBand {
  std::string description; ///< quantity and unit, e.g. "max_flow_height_vertical_m"
  std::string unit;        ///< GDAL unit type, e.g. "m", "m/s", "kPa"
  double nodata = -9999;
  /// Extra GDAL metadata items (key, value) on the dataset.
  std::vector<std::pair<std::string, std::string>> metadata;
};

/// Writes `values` (grid.size() floats, row 0 north) to `path`: DEFLATE-compressed, the grid's
/// geotransform and CRS WKT, band nodata/description/unit. Written to a temporary name and
/// renamed. Throws std::runtime_error with GDAL's message on failure.
void writeGeoTiff(const std::string& path, const RasterGrid& grid, const std::vector<float>& values,
                  const GeoTiffBand& band);

} // namespace talus
