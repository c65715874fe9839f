// Post-processing of a run's outputs (the `talus profile`, `map-stats`, `compare` and
// `series-stats` commands): profiles of map rasters along a polyline, statistics of one map
// (areas, volume, run-out along a path, ground elevations reached), a cell-by-cell comparison
// with a reference raster (e.g. AvaFrame's peak files), and a summary of series.csv (peaks, time
// to rest, discharged volumes, front speed against distance).
#pragma once

#include "io/common/polyline.h"
#include "io/common/raster_grid.h"
#include "io/output/time_series.h"

#include <Eigen/Dense>
#include <limits>
#include <string>
#include <vector>

namespace talus::analysis {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// A label from a map's path: "maps/rock/deposit_thickness.tif" -> "rock deposit_thickness",
/// "maps/x.tif" -> "x".
std::string defaultLabel(const std::string& path);

/// Band 1 of a north-up raster with square cells (any format GDAL reads); no-data is NaN.
/// Throws InputError naming the file.
DemRaster readRaster(const std::string& path);

/// Bilinear interpolation between cell centres at world (x, y). Within half a cell of the
/// raster's edge the outermost centres are extended; NaN outside the raster or where a cell the
/// interpolation needs is NaN.
double sample(const DemRaster& r, double x, double y);

/// `src` resampled (bilinearly, as `sample`) at the cell centres of `onto`.
DemRaster resample(const DemRaster& src, const RasterGrid& onto);

/// Values of every raster sampled every `step` metres along the line (and at its end).
struct Profile {
  std::vector<double> s, x, y;
  std::vector<std::vector<double>> values; ///< [raster][sample]
};
Profile profile(const Polyline& line, const std::vector<const DemRaster*>& rasters, double step);

/// Statistics of the cells whose value is at least `threshold` (NaN cells never count).
struct MapStats {
  double threshold = 0;
  size_t cells = 0;
  double area = 0;          ///< m2
  double max = kNaN;        ///< over all cells
  double mean = kNaN;       ///< over the counted cells
  double volume = 0;        ///< sum of the counted values times the cell area (m3 for a thickness)
  double groundMin = kNaN;  ///< lowest and highest ground under the counted cells (with a ground)
  double groundMax = kNaN;
  double runout = kNaN;     ///< farthest distance along the path of a counted cell (with a path)
  double runoutX = kNaN, runoutY = kNaN; ///< where that cell is
  bool runoutBeyondEnd = false;           ///< a counted cell lies beyond the path's end
};
/// `ground` (may be null) is sampled at each cell centre; only cells within `halfWidth` of the
/// path (may be null) count towards the run-out.
MapStats mapStats(const DemRaster& r, double threshold, const DemRaster* ground = nullptr,
                  const Polyline* path = nullptr, double halfWidth = std::numeric_limits<double>::infinity());

/// A simulated map against a reference on the reference's grid, at one threshold.
struct Comparison {
  double threshold = 0;
  MapStats sim, ref;        ///< sim: resampled onto the reference grid
  double areaBoth = 0;      ///< m2 where both reach the threshold
  double areaSimOnly = 0, areaRefOnly = 0;
  double overlap = kNaN;    ///< areaBoth / union (intersection over union, 1 = identical extents)
  double bias = kNaN;       ///< mean of sim - ref over the union
  double rmse = kNaN;       ///< root mean square of sim - ref over the union
};
/// `sim` is resampled onto `ref.grid`; cells where either is NaN are skipped.
Comparison compare(const DemRaster& simOnRef, const DemRaster& ref, double threshold, const Polyline* path = nullptr,
                   double halfWidth = std::numeric_limits<double>::infinity());
/// Per cell of `ref.grid`: 0 neither, 1 reference only, 2 both, 3 simulation only (NaN where
/// either is NaN).
std::vector<float> overlapClasses(const DemRaster& simOnRef, const DemRaster& ref, double threshold);

/// series.csv as written by a run.
SeriesTable readSeries(const std::string& path);

/// First time after the peak of `column` from which it stays below fraction x peak until the
/// end; NaN when it never does (or the column is absent).
double timeBelowFraction(const SeriesTable& t, const std::string& column, double fraction);

/// Front arrival time against distance along a path (from front_m_<path>): the first time the
/// front reached each distance of `s` (NaN where never), and the front speed there,
/// 2 h / (t(s + h) - t(s - h)).
struct FrontSpeed {
  std::vector<double> s, arrival, speed;
};
FrontSpeed frontSpeedAgainstDistance(const SeriesTable& t, const std::string& path, double step, double h);

} // namespace talus::analysis
