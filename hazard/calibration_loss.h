// How far a run is from an observed event, from AIMEC's measures on its (s, l) path grid
// (hazard/aimec.h). The observation is any combination of
//
//   footprint=FILE   a polygon file (deposit outline, affected area), or a raster (.asc, .tif:
//                    another model's peak field) read as where it exceeds the threshold; the
//                    run's footprint is where its `result` peak field (AIMEC's runoutResType,
//                    default ppr) exceeds the threshold (thresholdValue, default 1 kPa)
//   runout=X,Y       the observed run-out point, projected on the path to its distance s_obs
//   raster=FILE      a raster of the `raster_result` type (default the same as result): a
//                    deposit thickness from a DEM difference, another model's peak field
//
// and the loss is the weighted sum of these terms (weights default 1, all dimensionless):
//
//   footprint   alpha_FP + alpha_FN: the areas the run covers and the event did not, and the
//               event covered and the run did not, each over the event's area (AIMEC's
//               normalisation); 0 for a perfect match, 1 for a run of the right size in the
//               wrong place, 2 and more when it overshoots as well
//   runout      |s_run - s_obs| / s_obs: AIMEC's run-out (the last cross-section where the
//               field's cross-maximum exceeds the threshold) against the observed point's s,
//               as a fraction of s_obs (1 when the run reaches nothing)
//   raster      alpha_FP + alpha_FN at the threshold, plus the root-mean-square of run minus
//               observation over the union of both footprints divided by the observation's mean
//               over its own footprint (the misfit of the values, not only of the outline)
//
// Only the path grid's domain counts (AIMEC's domainWidth across the path), as in AIMEC.
#pragma once

#include "hazard/aimec.h"
#include "io/common/raster_grid.h"
#include "io/scene/ensemble_settings.h"
#include "io/terrain/polygon_set.h"

#include <memory>
#include <string>
#include <vector>

namespace talus::calibration {

enum class ObservedKind { Footprint, Runout, Raster };

struct Observation {
  ObservedKind kind = ObservedKind::Footprint;
  std::string text;      ///< as given, for messages
  std::string file;      ///< footprint and raster
  Eigen::Vector2d point{0, 0}; ///< runout (world x, y)
  double weight = 1;
};

/// "footprint=FILE", "runout=X,Y" or "raster=FILE". Throws InputError("--observed", ...) in one
/// line. The files are read (and checked) by ObservedEvent.
Observation parseObservation(const std::string& text);
/// "KIND=W" applied to every observation of that kind; throws InputError("--weight", ...).
void applyWeight(std::vector<Observation>& observations, const std::string& text);

struct LossTerms {
  double footprintFP = NAN, footprintFN = NAN;
  double runoutRun = NAN, runoutObserved = NAN, runout = NAN; ///< s (m) and the relative error
  double rasterFP = NAN, rasterFN = NAN, rasterMisfit = NAN;
  double total = NAN; ///< NaN: the run wrote no peak file of a needed type
};

class ObservedEvent {
public:
  /// Reads the observation's files and the path. `settings` gives the path (two points at
  /// least), domainWidth, result and threshold; `rasterResult` empty = settings.runoutResult.
  /// `ground` (may be null) gives slope areas. Throws InputError naming the file (unreadable, no
  /// polygon, not a raster) or the path ("calibration needs a path").
  ObservedEvent(std::vector<Observation> observations, const EnsembleSettings& settings, std::string rasterResult,
                std::shared_ptr<const DemRaster> ground);

  /// The loss of the run in `runDir` (its peakFiles/). The first call fixes the path grid at
  /// the run's cell size.
  LossTerms evaluate(const std::string& runDir);

  /// Header and values of the terms for a CSV ("footprint_fp,footprint_fn,...,loss"): only the
  /// observed kinds' columns.
  std::string csvHeader() const;
  std::string csvValues(const LossTerms& t) const;

  /// Per path-grid point for the picture of a run against the event: 0 neither, 1 event only,
  /// 2 both, 3 run only (the first area observation: footprint, else raster), and the grid.
  std::vector<uint8_t> classes(const std::string& runDir);
  const aimec::Transform* transform() const { return transform_.get(); }
  const std::vector<Observation>& observations() const { return observations_; }
  const EnsembleSettings& settings() const { return settings_; }

private:
  bool has(ObservedKind k) const;
  void prepare(double cellSize); ///< the transform and the observations on it
  /// The run's peak field of `type` on the path grid (no data: 0), {} without the file.
  std::vector<float> runField(const std::string& runDir, const std::string& type);
  /// 1 where the run's field exceeds the threshold, else 0: its footprint.
  std::vector<float> footprintOf(const std::vector<float>& run) const;

  std::vector<Observation> observations_;
  EnsembleSettings settings_;
  std::string rasterResult_;
  std::shared_ptr<const DemRaster> ground_;
  std::unique_ptr<aimec::Transform> transform_;
  std::vector<PolygonSet> polygons_;      ///< footprint observations (their union counts)
  std::vector<DemRaster> footprintRasters_; ///< footprints given as rasters: where > threshold
  std::unique_ptr<DemRaster> rasterFile_; ///< the raster observation
  std::vector<float> footprint_, raster_; ///< the observations on the path grid
  double sObserved_ = NAN;
};

} // namespace talus::calibration
