// The run-up and flooding map of a reservoir: per map cell, the highest water surface reached
// during the run (maps/max_water_surface.tif, m in the DEM's vertical datum) and how far that
// lies above the water's initial level (maps/water_surface_rise.tif, m), with a PNG quick-look
// of the rise. Written with the hazard maps, on their grid, for scenes with water.
//
// The surface in a cell is read as the wave gauges read it (io/output/water_gauges.h): the water
// volume in the cell (particles by the cell they are in, volume m / rho0) spread over the cell's
// area, above the bottom of the water there (the lowest particle less half a particle spacing).
// The initial level of a cell is its surface at the start; a cell dry at the start takes the
// initial level of the nearest cell that was wet (4-neighbour steps), so on a shore the rise is
// the run-up height above the still water the wave came from. NaN (no data) where water never was.
// Cells are a few particles wide: the surface is their mean over the cell, so a crest narrower
// than a cell reads lower than a gauge on it. Volumes are fixed-point integers and bottoms minima
// (io/output/step_parts.h), so under ranks each rank makes its own cells' part.
#pragma once

#include "io/output/output_observer.h"
#include "io/common/raster_grid.h"

#include <memory>
#include <string>
#include <vector>

namespace talus {

class WaterSurfaceMap final : public OutputObserver {
public:
  /// `grid` as the hazard maps' (the DEM's grid or the domain's); `dem` (may be null) shades the
  /// quick-look; `waterMaterials` as OutputSettings::waterMaterials; `particleSpacing` (m).
  WaterSurfaceMap(std::string outDir, RasterGrid grid, std::shared_ptr<const DemRaster> dem,
                  std::vector<std::string> waterMaterials, double particleSpacing, bool quicklook);

  std::string name() const override { return "water_surface_map"; }
  /// Finds the water; a scene without water makes this output write nothing.
  void onStart(const Simulation& sim) override;
  void onStep(const Simulation& sim, double dt) override;
  bool readsEveryStep() const override { return true; }
  /// In parts: each rank's fixed-point water volume and lowest water particle per cell.
  void prepareParts(const Simulation& sim) override;
  bool partDue(const Simulation&) const override { return !water_.empty(); }
  void part(const Simulation& local, const PartBounds& b, bool keep, std::vector<char>& out) override;
  void onStepParts(const Simulation& sim, double dt, const PartBounds& b,
                   const std::vector<std::string_view>& parts) override;
  void onFinish(const Simulation& sim, bool completed) override;
  void save(StateArchive& a, const std::string& prefix) const override;
  void load(const StateArchive& a, const std::string& prefix) override;
  std::vector<std::pair<std::string, std::string>> summary() const override;

  /// On the whole grid, NaN where water never was: the highest surface (world z) and its rise
  /// above the initial level.
  std::vector<float> maxSurface() const;
  std::vector<float> rise() const;
  const RasterGrid& grid() const { return grid_; }

  bool partsByOwner() const override { return true; }
  void partByOwner(const Simulation& local, const PartBounds& b, int self, std::vector<std::vector<char>>& outs) override;
  void ownedResult(bool state, std::vector<char>& out) override;
  void mergeResults(const Simulation& sim, bool state, const std::vector<std::string_view>& others) override;

private:
  /// Sums `local`'s water into the scratch (volume_, bottom_, touched_) in the units of `b`.
  void sumOwn(const Simulation& local, const PartBounds& b);
  /// The touched cells owned by rank r of `ranks` as outs[r]'s part, cleared from the scratch;
  /// those `self` owns stay (self -1: none).
  void writeTouched(std::vector<char>* outs, int ranks, int self);
  /// The water surface of every window cell now (NaN where dry).
  void surfaces(const Simulation& sim, std::vector<float>& out);
  /// Adds the parts' cells to this process's kept one, and the surface of every cell touched;
  /// returns the cells touched and empties the scratch.
  std::vector<uint32_t> mergeParts(const Simulation& sim, const PartBounds& b, const std::vector<std::string_view>& parts,
                  std::vector<float>& out);
  int volumeUnit(const Simulation& sim, const PartBounds& b) const;
  std::vector<float> onGrid(const std::vector<float>& window) const;

  std::string outDir_;
  RasterGrid grid_, window_;
  int c0_ = 0, r0_ = 0;
  std::shared_ptr<const DemRaster> dem_;
  std::vector<std::string> waterMaterials_;
  double spacing_;
  bool quicklook_;
  std::vector<size_t> water_; ///< indices of the water groups
  double originZ_ = 0;
  std::vector<float> initial_, max_;   ///< per window cell (NaN: dry)
  std::vector<int64_t> volume_;        ///< scratch per window cell: fixed-point volume
  std::vector<float> bottom_;          ///< and lowest particle (infinite: none yet)
  std::vector<uint32_t> touched_;
};

} // namespace talus
