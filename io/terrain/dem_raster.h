// Digital elevation models: reading any raster GDAL reads, no-data filling, Gaussian smoothing,
// writing GeoTIFFs, and the bilinear height field the terrain level set and terrain bodies use.
#pragma once

#include "io/common/input_error.h"

#include "io/common/raster_grid.h"

#include <stdexcept>
#include <string>
#include <vector>

namespace talus {


struct DemReadOptions {
  /// Fill no-data cells (see fillNodata) instead of refusing a DEM that has them.
  bool fillNodata = false;
  /// Keep no-data cells as NaN instead (a post-event DEM covering only the scar).
  bool keepNodata = false;
  /// CRS to assume when the file has none (anything GDAL's SetFromUserInput takes, e.g.
  /// "EPSG:31287"); an error when the file has a different one.
  std::string assignCrs;
};

/// Band 1 of `path` as float heights (NaN for no-data). Refuses, naming the file: a missing or
/// unreadable file, a rotated geotransform, non-square cells, and no-data cells unless
/// options.fillNodata (then they are filled and `filledCells` says how many).
DemRaster readDem(const std::string& path, const DemReadOptions& options = {}, size_t* filledCells = nullptr);

/// Number of NaN cells.
size_t countNodata(const DemRaster& dem);

/// The search radius of fillNodata, in cells.
inline constexpr int kMaxFillCells = 1000;

/// Fills every NaN cell by GDAL's inverse-distance interpolation from the valid cells around
/// it (GDALFillNodata, the algorithm of gdal_fillnodata, with a search radius spanning the
/// raster up to kMaxFillCells and 2 smoothing passes over the filled cells only). Returns the
/// number of cells filled. Throws InputError when no cell is valid or a hole is out of reach.
size_t fillNodata(DemRaster& dem);

/// Gaussian smoothing of "radius" R metres: the Gaussian's 1/e^2 radius, i.e. sigma = R/2,
/// truncated at 3 sigma (1.5 R). Separable, and no-data aware by normalised convolution: NaN
/// cells stay NaN and do not contribute, and near the raster edge the kernel is renormalised
/// over the cells that exist. R = 0 leaves the DEM unchanged.
void smoothDem(DemRaster& dem, double radius);

/// Writes a single-band float32 GeoTIFF (no-data -9999 where NaN), the CRS included.
void writeDemGeoTiff(const DemRaster& dem, const std::string& path);

/// CRS given as EPSG code, WKT, PROJ string...  ->  WKT. Throws InputError.
std::string crsToWkt(const std::string& userInput);
/// Same CRS (GDAL's IsSame) when both are non-empty; true when either is unknown.
bool sameCrs(const std::string& wktA, const std::string& wktB);
/// A short name for messages, e.g. "MGI / Austria Lambert (EPSG:31287)".
std::string crsName(const std::string& wkt);

/// Bilinear interpolation of per-cell-centre `values` on `g` at world (x, y), clamped like
/// HeightField::height.
double sampleBilinear(const RasterGrid& g, const std::vector<float>& values, double x, double y);

/// The terrain surface: bilinear interpolation of the heights at cell centres (a DEM's values
/// are point samples at the centres), held constant beyond the outermost centres. World
/// coordinates in the DEM's CRS. NaN cells make the patches touching them NaN. Keeps a
/// pointer to `dem`, which must outlive it.
class HeightField {
public:
  explicit HeightField(const DemRaster& dem);
  const DemRaster& dem() const { return *dem_; }
  const RasterGrid& grid() const { return dem_->grid; }

  double height(double x, double y) const;
  /// Height and the gradient of the bilinear patch containing (x, y).
  double heightAndGradient(double x, double y, double& gx, double& gy) const;
  /// Smooth gradient: central differences at the cell centres, interpolated bilinearly. Used for
  /// slopes (masks, slope-normal thickness), where the patchwise gradient would be blocky.
  void slopeGradient(double x, double y, double& gx, double& gy) const;
  /// Slope angle (radians) from slopeGradient.
  double slope(double x, double y) const;
  /// World extent of the raster (cell edges).
  double xmin() const { return dem_->grid.originX; }
  double xmax() const { return dem_->grid.originX + dem_->grid.nx * dem_->grid.cellSize; }
  double ymin() const { return dem_->grid.originY - dem_->grid.ny * dem_->grid.cellSize; }
  double ymax() const { return dem_->grid.originY; }
  bool covers(double x, double y) const { return x >= xmin() && x <= xmax() && y >= ymin() && y <= ymax(); }
  void range(float& lo, float& hi) const { lo = hmin_, hi = hmax_; }

private:
  const DemRaster* dem_;
  std::vector<float> gx_, gy_; ///< central-difference gradient at the cell centres
  float hmin_ = 0, hmax_ = 0;
};

} // namespace talus
