// Path analysis as AvaFrame's ana3AIMEC does it (docs/moduleAna3AIMEC.rst, aimecTools.py at the
// 2025-11 snapshot): peak fields are resampled onto a thalweg-following grid of (s, l)
// coordinates, s the horizontal distance along the path from its first point, l the distance
// across it (positive to the left, looking down the path), and analysed per cross-section:
//
//   crossMax(s)  = max over l of A(s, l);  crossMean(s) = area-weighted mean over cells with A > 0
//   crossIntegral(s) = sum over l of max(A, 0) times the cell's area, per metre along s (Talus's:
//                  an erosion depth's eroded volume per metre of path)
//   run-out      = the last s where crossMax(s) > A_lim (strictly, as AIMEC); its start the first
//   deltaSXY     = sRunout - sStart; runout angle atan((z(sStart) - z(sRunout)) / deltaSXY)
//   MMA, AMA     = max and mean of crossMax over [sStart, sRunout]
//   areas        = true positive (both > A_lim), false positive (simulation only), false
//                  negative (reference only), true negative; normalised by the reference's
//                  area TP + FN (what the AIMEC code does; its docs write TP + FP)
//
// Differences to AvaFrame, all of them below a cell: the cross-sections sit at vertices of the
// path resampled every cell (AIMEC splits the domain edges), and cell areas are the quads
// between neighbouring grid points times the DEM's slope factor.
#pragma once

#include "io/common/polyline.h"
#include "io/common/raster_grid.h"

#include <cstdint>
#include <limits>
#include <vector>

namespace talus::aimec {

constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

/// The (s, l) grid: point (i, k) is cross-section i, lane k; row-major, ns rows of nl.
struct Transform {
  std::vector<double> s, l;   ///< s per cross-section, l per lane (m)
  std::vector<double> x, y;   ///< world position of every point
  std::vector<double> area;   ///< cell area (m2): real (slope) area when made with a DEM
  std::vector<double> zThalweg; ///< ground on the path per cross-section (NaN without DEM)
  size_t ns = 0, nl = 0;
  double cellSize = 0, width = 0;
  size_t index(size_t i, size_t k) const { return i * nl + k; }
};

/// The grid for `path` (at least two points), `width` across (AIMEC's domainWidth, default 600 m)
/// and `cellSize` spacing (AIMEC's cellSizeSL: the reference raster's cell). `dem` (may be null)
/// gives elevations and slope areas. Throws std::invalid_argument on a bad path or size.
Transform makeTransform(const Polyline& path, double width, double cellSize, const DemRaster* dem = nullptr);

/// A raster resampled bilinearly between cell centres at the grid points; NaN outside it or
/// where it has no data.
std::vector<float> resample(const Transform& t, const DemRaster& raster);

struct PathStats {
  double threshold = 0;
  std::vector<double> crossMax, crossMean; ///< per cross-section (NaN where no data at all)
  /// Per cross-section, the field's positive values times their cell areas, per metre along s
  /// (an erosion depth: the eroded volume per metre of path); NaN where no data at all.
  std::vector<double> crossIntegral;
  bool found = false;                      ///< some crossMax exceeds the threshold
  size_t iStart = 0, iRunout = 0;
  double sStart = kNaN, sRunout = kNaN, lRunout = kNaN, xRunout = kNaN, yRunout = kNaN;
  double sMeanRunout = kNaN, xMeanRunout = kNaN, yMeanRunout = kNaN;
  double deltaSXY = kNaN, zRelease = kNaN, zRunout = kNaN, deltaZ = kNaN, runoutAngle = kNaN;
  double mma = kNaN, ama = kNaN;  ///< max and mean of crossMax on [sStart, sRunout]
  double fieldMax = kNaN;         ///< maximum over the whole (s, l) grid
};
PathStats analyse(const Transform& t, const std::vector<float>& field, double threshold);

/// Area classes of a simulation against a reference (both resampled on `t`) from cross-section
/// `start` on (AIMEC's start of the run-out area; 0 = everywhere).
struct AreaComparison {
  double threshold = 0;
  double tp = 0, fp = 0, fn = 0, tn = 0; ///< m2
  double referenceArea = 0;              ///< tp + fn
  double alphaTP = kNaN, alphaFP = kNaN, alphaFN = kNaN, alphaTN = kNaN;
  double sRunoutSim = kNaN, sRunoutRef = kNaN, runoutDifference = kNaN; ///< simulation - reference (m)
  /// Per grid point: 0 neither, 1 reference only, 2 both, 3 simulation only (the classes of
  /// `talus compare`'s map), 255 before `start` or without data.
  std::vector<uint8_t> classes;
};
AreaComparison compareAreas(const Transform& t, const std::vector<float>& sim, const std::vector<float>& ref,
                            double threshold, size_t start = 0);

/// AIMEC's start of the run-out area: the first cross-section past the split point (nearest
/// cross-section; none: the path's start) where the thalweg's slope falls below `angle` degrees
/// and stays below for `dsMin` metres. ns when there is none; 0 without elevations.
size_t runoutAreaStart(const Transform& t, double angle, const Eigen::Vector2d* splitPoint, double dsMin = 30);

} // namespace talus::aimec
