// Discharge through a user section ([[output.sections]]): a vertical surface over a polyline in
// world xy, optionally limited to [z_min, z_max].
//
// Every step, each particle's path segment from x - dt v to x (the engine moves particles by
// exactly dt v) is tested against the section; a crossing adds the particle's volume (mass /
// reference density) with its sign. The columns are that signed volume over the time since the
// previous row (m3/s), so a row is the mean over its interval and never misses a crossing.
// Positive flow crosses from the right-hand side of the polyline (walking from its first to its
// last point) to its left-hand side: draw a section from the left bank to the right bank,
// looking downstream, and downstream discharge is positive (as in HEC-RAS).
#pragma once

#include "io/output/output_settings.h"
#include "io/output/series_columns.h"

namespace talus {

class SectionDischarge final : public SeriesColumns {
public:
  explicit SectionDischarge(SectionSpec spec) : spec_(std::move(spec)) {}

  void onStart(const Simulation& sim) override;
  std::vector<std::string> header() const override;
  void onStep(const Simulation& sim, double dt) override;
  void sample(const Simulation& sim, double elapsed, std::vector<double>& row) override;
  void save(StateArchive& a, const std::string& prefix) const override { a.putVector(prefix + "volume", volume_); }
  void load(const StateArchive& a, const std::string& prefix) override { a.getVector(prefix + "volume", volume_); }

  /// Signed volume (m3) per material group crossed since the last sample.
  const std::vector<double>& pendingVolume() const { return volume_; }

private:
  SectionSpec spec_;
  std::vector<Eigen::Vector2d> local_; ///< polyline in the local frame
  Eigen::Vector2d lo_, hi_;            ///< its bounding box
  double zMin_ = 0, zMax_ = 0;         ///< local
  std::vector<std::string> materials_;
  std::vector<double> volume_;
};

} // namespace talus
