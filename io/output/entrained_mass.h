// Entrained mass of erodible covers seeded as particles, over time (series.csv): for each
// material in [output.maps] erodible, the mass that has left the places it lay at the start,
// rho x sum over grid node columns of max(0, V0 - V), V the material's volume splatted onto the
// node columns (bilinear, spacing dx) now and V0 at the start. The erosion_depth map's measure
// (initial minus present thickness where positive) integrated, sampled through the run. Covers
// made erodible fields have their own column (entrained_mass_kg_<cover>, engine/erodible_bed.h).
// In parts: each process splats its own particles as fixed-point volumes (io/output/step_parts.h)
// and sends its columns at a row; rank 0 adds them per column, so V is the same at any rank count.
#pragma once

#include "io/output/series_columns.h"

#include <cstdint>
#include <unordered_map>

namespace talus {

class EntrainedMassColumns final : public PartsColumns {
public:
  /// `materials`: the erodible materials' names; those absent from the scene are ignored.
  explicit EntrainedMassColumns(std::vector<std::string> materials) : names_(std::move(materials)) {}
  /// From every particle: the groups and their volumes per column at the start.
  void onStart(const Simulation& sim) override;
  /// The groups only: the start's volumes are rank 0's.
  void prepareParts(const Simulation& local) override;
  bool any() const { return !groups_.empty(); }
  std::vector<std::string> header() const override;
  /// Per erodible material: its count of columns, then (column, volume in units) sorted by column.
  void part(const Simulation& local, const PartBounds& b, std::vector<char>& out) const override;
  void sampleParts(const Simulation& sim, double elapsed, const PartBounds& b,
                   const std::vector<std::string_view>& parts, std::vector<double>& row) override;

private:
  using Columns = std::unordered_map<uint64_t, double>;
  /// The volume (m^3) of each erodible group's particles per node column, from every process's part.
  std::vector<Columns> volumesFrom(const Simulation& sim, const PartBounds& b,
                                   const std::vector<std::string_view>& parts) const;
  static int unit(const Simulation& sim, const PartBounds& b);

  std::vector<std::string> names_;
  std::vector<int> groups_;     ///< positions in sim.groups()
  std::vector<std::string> groupNames_;
  std::vector<Columns> start_;  ///< per erodible group: its volume per column at the start
};

} // namespace talus
