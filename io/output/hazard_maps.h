// Hazard maps: per raster column, maxima over the run of flow height (vertical and slope-normal),
// speed and dynamic pressure, plus the final deposit and the erosion of erodible covers; written
// at the end as GeoTIFFs on the DEM's grid and CRS (maps/*.tif) with PNG quick-looks; also the
// initial thickness and, with a DEM, the ground as simulated, so profiles and run-up elevations
// can be taken from the maps alone.
//
// Every accumulation splats each particle's volume (mass / reference density), mass and speed
// onto the four nearest cell centres with bilinear weights (cloud-in-cell), so a uniform layer
// gives a uniform thickness even with few particles per cell. Per column:
//   flow height (vertical) h = sum V / cell area
//   slope-normal height       = h cos(slope)
//   speed                     = sum m |v| / sum m   (mass-weighted mean)
//   dynamic pressure          = sum m |v|^2 / sum V (= rho v^2 for one material), in kPa
// The sums are fixed-point integers (units below 2^-40 of the largest particle's value), so they
// are exact in any order: under ranks each process sums its own particles into a part and rank 0
// adds the parts (OutputObserver::readsEveryStep), with the bytes of one process.
#pragma once

#include "io/output/output_settings.h"
#include "io/output/output_observer.h"
#include "io/output/run_context.h"
#include "io/common/raster_grid.h"

#include <memory>

namespace talus {

class HazardMaps final : public OutputObserver {
public:
  enum Quantity {
    MaxHeightVertical, MaxHeightNormal, MaxSpeed, MaxPressure, Deposit, Erosion,
    Initial, ///< thickness (vertical) of all particles at the start
    Ground,  ///< the ground as simulated (with a DEM only; not per material)
    kQuantities
  };
  static constexpr float kNoData = -9999.f;

  /// `grid` georeferences the written rasters; `dem` (may be null) holds heights on that same
  /// grid for the slope and the hillshade. Without a DEM the slope comes from the terrain SDF
  /// (or is zero without terrain).
  HazardMaps(std::string outDir, RasterGrid grid, std::shared_ptr<const DemRaster> dem, MapSettings settings);
  ~HazardMaps() override;

  /// The grid maps use when a scene has no DEM: the domain's xy extent in cells of `cellSize`.
  static RasterGrid domainGrid(const RunContext& run, double cellSize);

  std::string name() const override { return "hazard_maps"; }
  void onStart(const Simulation& sim) override;
  void onStep(const Simulation& sim, double dt) override;
  bool readsEveryStep() const override { return true; }
  void prepareParts(const Simulation& sim) override;
  bool partDue(const Simulation& sim) const override;
  void part(const Simulation& local, const PartBounds& b, bool keep, std::vector<char>& out) override;
  void onStepParts(const Simulation& sim, double dt, const PartBounds& b,
                   const std::vector<std::string_view>& parts) override;
  bool partsByOwner() const override;
  void partByOwner(const Simulation& local, const PartBounds& b, int self, std::vector<std::vector<char>>& outs) override;
  bool resultDue() const override;
  void ownedResult(bool state, std::vector<char>& out) override;
  void mergeResults(const Simulation& sim, bool state, const std::vector<std::string_view>& others) override;
  void onFinish(const Simulation& sim, bool completed) override;
  void save(StateArchive& a, const std::string& prefix) const override;
  void load(const StateArchive& a, const std::string& prefix) override;

  /// Quantity q on the whole grid (kNoData outside the domain), for all material (layer 0) or
  /// for material group i (layer 1 + i, when per_material). Deposit and erosion exist after
  /// onFinish; erosion is zero where nothing erodible was. Ground is the DEM's heights (NaN
  /// without a DEM).
  std::vector<float> raster(Quantity q, int layer = 0) const;
  const RasterGrid& grid() const { return grid_; }
  size_t accumulations() const { return accumulations_; }

  /// File stem, GeoTIFF band description and unit of a quantity.
  static const char* stem(Quantity q);
  static const char* band(Quantity q);
  static const char* unit(Quantity q);

  /// The film's outcome: {"animation", file or why it was not made} (when enabled).
  std::vector<std::pair<std::string, std::string>> summary() const override;

private:
  bool animationFrameDue(double time) const;
  void writeFrame(double time); ///< rank 0: the film frame of the accumulation just folded
  void makeFilm();
  std::string animationOutcome_;
  struct Impl;
  static void addBedErosion(Impl& m, const Simulation& sim);
  std::unique_ptr<Impl> impl_;
  std::string outDir_;
  RasterGrid grid_;
  std::shared_ptr<const DemRaster> dem_;
  MapSettings settings_;
  size_t accumulations_ = 0;
};

} // namespace talus
