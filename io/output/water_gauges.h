// Wave gauges ([[output.gauges]]): the water's surface elevation at fixed points of world xy, as
// an array of capacitance or ultrasonic gauges along a flume or around a reservoir records it.
//
// A gauge reads the water particles within a square footprint of half-width `radius` around its
// point, weighted by a tent (1 - |dx|/r)(1 - |dy|/r)/r^2, whose integral is 1: the sum of the
// weighted particle volumes m/rho0 is the water depth there, exactly for a layer seeded on a
// lattice whose spacing divides r. The surface is that depth above the bottom of the water in the
// footprint (the lowest contributing particle less half a particle spacing), so water over a slide,
// a bed or a step reads its own surface, not the ground's. NaN where no water is in the footprint.
// Volumes are at the reference density: a Tait water compressed by its own weight reads low by
// rho0 g d / (rho0 c^2) of its depth (0.3 % for 0.3 m of water at c = 30 m/s). The volumes are
// fixed-point sums (io/output/step_parts.h), so ranks read their own particles.
#pragma once

#include "io/output/output_settings.h"
#include "io/output/series_columns.h"

namespace talus {

/// The water groups of a run: those named in `names`, or every group of model "water" when the
/// list is empty.
std::vector<const MaterialGroup*> waterGroups(const Simulation& sim, const std::vector<std::string>& names);
/// The same as indices into sim.groups(): what holds for another process's groups too.
std::vector<size_t> waterGroupIndices(const Simulation& sim, const std::vector<std::string>& names);

class WaterGauges final : public PartsColumns {
public:
  /// `waterMaterials` as OutputSettings::waterMaterials; `particleSpacing` (m) the seeding
  /// spacing. Expects at least one gauge.
  WaterGauges(std::vector<GaugeSpec> gauges, std::vector<std::string> waterMaterials, double particleSpacing);

  /// Throws std::runtime_error when the scene has no water (a gauge would never read anything).
  void onStart(const Simulation& sim) override;
  std::vector<std::string> header() const override;
  /// In parts: each process's tent-weighted volumes per gauge as fixed-point integers and its
  /// lowest water particle there.
  void part(const Simulation& local, const PartBounds& b, std::vector<char>& out) const override;
  void sampleParts(const Simulation& sim, double elapsed, const PartBounds& b,
                   const std::vector<std::string_view>& parts, std::vector<double>& row) override;

  /// The surface elevation (world z, m) at every gauge now, NaN where dry; one pass over the
  /// water particles whatever the number of gauges.
  std::vector<double> surfaces(const Simulation& sim) const;
  /// The water column at every gauge now: its volume per unit area in the footprint (m), 0 where
  /// dry, wherever it lies (a jet passing over a gauge adds its thickness, where `surfaces`
  /// reads its elevation).
  std::vector<double> depths(const Simulation& sim) const;

private:
  std::vector<GaugeSpec> gauges_;
  std::vector<std::string> waterMaterials_;
  double spacing_;
  /// The fixed-point unit 2^unit of gauge k's depth sums under the bounds `b`.
  int unit(const Simulation& sim, const PartBounds& b, size_t k) const;
  std::vector<double> surfacesFrom(const Simulation& sim, const PartBounds& b,
                                   const std::vector<std::string_view>& parts) const;
  std::vector<size_t> water_; ///< indices into the groups (rank 0 starts on its gathered copy)
  std::vector<double> radius_; ///< per gauge (m)
  double bucket_ = 1;          ///< side of the hash cells that find a particle's gauges (m)
  std::vector<std::pair<long long, int>> buckets_; ///< (cell key, gauge), sorted
};

} // namespace talus
