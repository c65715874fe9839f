// ESRI ASCII grids (Arc/Info ASCII, *.asc) through GDAL's AAIGrid driver: the format AvaFrame
// reads and writes when its DEM is one.
#pragma once

#include "io/common/raster_grid.h"

#include <string>
#include <vector>

namespace talus {

/// Writes `values` (grid.size() floats, row 0 north) to `path` with the header ncols, nrows,
/// xllcorner, yllcorner, cellsize, NODATA_value, 9 significant digits (float32 round-trips), and
/// a .prj beside it when the grid has a CRS. Written under temporary names and renamed. Throws
/// std::runtime_error with GDAL's message on failure.
void writeAsciiGrid(const std::string& path, const RasterGrid& grid, const std::vector<float>& values,
                    double nodata = -9999);

} // namespace talus
