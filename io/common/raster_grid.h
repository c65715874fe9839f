// A north-up georeferenced raster (the DEM's grid): the common currency of terrain input
// (io/dem_raster) and map output (hazard GeoTIFFs, PNG quick-looks).
#pragma once

#include <cmath>
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

/// The cells of `g` that the world rectangle [xmin, xmax] x [ymin, ymax] touches, as a grid of
/// their own (same cells, origin shifted); c0, r0 receive its first column and row in `g`. Its
/// nx or ny is 0 when the rectangle misses `g`.
inline RasterGrid windowOf(const RasterGrid& g, double xmin, double ymin, double xmax, double ymax, int& c0, int& r0) {
  const double cs = g.cellSize;
  auto clampTo = [](double v, int hi) { return v < 0 ? 0 : v > hi ? hi : int(v); };
  c0 = clampTo(std::floor((xmin - g.originX) / cs), g.nx);
  r0 = clampTo(std::floor((g.originY - ymax) / cs), g.ny);
  const int c1 = clampTo(std::ceil((xmax - g.originX) / cs), g.nx), r1 = clampTo(std::ceil((g.originY - ymin) / cs), g.ny);
  RasterGrid w = g;
  w.nx = c1 > c0 ? c1 - c0 : 0, w.ny = r1 > r0 ? r1 - r0 : 0;
  w.originX = g.originX + c0 * cs, w.originY = g.originY - r0 * cs;
  return w;
}

/// Elevations on a RasterGrid, row-major as above; NaN marks no-data.
struct DemRaster {
  RasterGrid grid;
  std::vector<float> height;
  std::string sourcePath;
};

} // namespace talus
