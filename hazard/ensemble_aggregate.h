// An ensemble's summary from its members' AvaFrame peak files (member_NNN/peakFiles/*, read
// with GDAL): per result type the exceedance probability P(peak > threshold) (the fraction of
// completed members, a strict > as AvaFrame's probAna), the mean and quantiles per cell; the
// run-out of every member along the path (AIMEC's criterion) and its distribution; a CSV of
// member, parameters and outcomes; Morris effects for a Morris plan. Maps are GeoTIFFs on the
// DEM's grid with PNG quick-looks. The members' peak files are also linked into DIR/peakFiles so
// AvaFrame's probAna and AIMEC read the whole ensemble as one folder of simulations.
#pragma once

#include "hazard/ensemble_plan.h"
#include "io/common/raster_grid.h"
#include "io/scene/ensemble_settings.h"

#include <memory>
#include <string>
#include <vector>

namespace talus::ensemble {

/// Peak file of `type` (pft, pfv, ppr, pfd) in a member folder: peakFiles/*_<type>.tif, else
/// .asc; "" when none.
std::string findPeakFile(const std::string& memberDir, const std::string& type);

/// Per-cell statistics over member rasters on one grid; NaN cells are left out and a cell no
/// member has data for is NaN.
std::vector<float> exceedanceProbability(const std::vector<const DemRaster*>& members, double threshold);
std::vector<float> cellMean(const std::vector<const DemRaster*>& members);
/// Quantile q by linear interpolation between order statistics (numpy's default): position
/// q (n - 1) in the sorted values.
std::vector<float> cellQuantile(const std::vector<const DemRaster*>& members, double q);

struct MemberOutcome {
  bool completed = false;
  double wallSeconds = NAN;
  double runout = NAN, runoutX = NAN, runoutY = NAN; ///< AIMEC sRunout along the path (m)
  double maxPft = NAN, maxPfv = NAN, maxPpr = NAN;
  double areaPft = NAN; ///< m2 where pft exceeds the first pft threshold (or 0.1 m)
};

struct AggregateReport {
  std::vector<MemberOutcome> members;
  std::vector<std::string> files; ///< written, relative to the ensemble folder
};

/// Reads the completed members of `plan` under `dir` and writes the summary there (maps/,
/// members.csv, runout.csv and runout.png with a path, morris.csv for a Morris plan,
/// peakFiles/). `ground` (may be null) shades the PNGs. Throws when members disagree on the grid.
AggregateReport aggregate(const std::string& dir, const Plan& plan, const EnsembleSettings& settings,
                          std::shared_ptr<const DemRaster> ground);

} // namespace talus::ensemble
