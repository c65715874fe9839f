// A north-up georeferenced raster (the DEM's grid): the common currency of terrain input
// (io/dem_raster) and map output (hazard GeoTIFFs, PNG quick-looks).
#pragma once

#include <cstddef>
#include <string>
#include <vector>

namespace talus {

/// Same conventions as a GDAL geotransform without rotation: (originX, originY) is the
/// top-left (north-west) corner of the raster, row 0 is the northern row, columns go east.
struct RasterGrid {
  int nx = 0, ny = 0;      ///< columns, rows
  double originX = 0;      ///< world x of the west edge (m, in the CRS)
  double originY = 0;      ///< world y of the north edge
  double cellSize = 1;     ///< square cells (m)
  std::string crsWkt;      ///< CRS as WKT ("" when unknown)

  double cellCentreX(int col) const { return originX + (col + 0.5) * cellSize; }
  double cellCentreY(int row) const { return originY - (row + 0.5) * cellSize; }
  size_t index(int col, int row) const { return size_t(row) * size_t(nx) + size_t(col); }
  size_t size() const { return size_t(nx) * size_t(ny); }
  /// Column and row of the cell containing world (x, y); false when outside.
  bool locate(double x, double y, int& col, int& row) const {
    const double c = (x - originX) / cellSize, r = (originY - y) / cellSize;
    if (c < 0 || r < 0 || c >= nx || r >= ny) return false;
    col = int(c), row = int(r);
    return true;
  }
};

/// Elevations on a RasterGrid, row-major as above; NaN marks no-data.
struct DemRaster {
  RasterGrid grid;
  std::vector<float> height;
  std::string sourcePath;
};

} // namespace talus
