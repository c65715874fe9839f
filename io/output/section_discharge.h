// Discharge through a user section ([[output.sections]]): a vertical surface over a polyline in
// world xy, optionally limited to [z_min, z_max].
//
// Every step, each particle's path segment from x - dt v to x (the engine moves particles by
// exactly dt v) is tested against the section; a crossing adds the particle's volume (mass /
// reference density) with its sign. The columns are that signed volume over the time since the
// previous row (m3/s), so a row is the mean over its interval and never misses a crossing.
// Each process counts its own particles' crossings every step (stepLocal) as a running
// fixed-point sum of signed mass (io/output/step_parts.h), in one unit for the whole run, so the
// rows are the same bytes at any rank and thread count; a row is the change of the sum of every
// process's total since the previous row.
// Positive flow crosses from the right-hand side of the polyline (walking from its first to its
// last point) to its left-hand side: draw a section from the left bank to the right bank,
// looking downstream, and downstream discharge is positive (as in HEC-RAS).
#pragma once

#include "io/output/output_settings.h"
#include "io/output/series_columns.h"

namespace talus {

class SectionDischarge final : public PartsColumns {
public:
  explicit SectionDischarge(SectionSpec spec) : spec_(std::move(spec)) {}

  void onStart(const Simulation& sim) override;
  std::vector<std::string> header() const override;
  /// Adds the crossings of `local`'s particles in the step of `dt` just taken to this process's total.
  void stepLocal(const Simulation& local, double dt) override;
  bool accumulates() const override { return true; }
  /// This process's totals so far (one 128-bit integer per material).
  void part(const Simulation& local, const PartBounds& b, std::vector<char>& out) const override;
  void sampleParts(const Simulation& sim, double elapsed, const PartBounds& b,
                   const std::vector<std::string_view>& parts, std::vector<double>& row) override;
  void handOver(std::vector<char>& out) override;
  /// @throw std::runtime_error if `in` is not one total per material
  void takeOver(std::string_view in) override;
  void save(StateArchive& a, const std::string& prefix) const override;
  void load(const StateArchive& a, const std::string& prefix) override;

private:
  using Sum = __int128;
  void putTotals(std::vector<char>& out) const;
  SectionSpec spec_;
  std::vector<Eigen::Vector2d> local_; ///< polyline in the local frame
  Eigen::Vector2d lo_, hi_;            ///< its bounding box
  double zMin_ = 0, zMax_ = 0;         ///< local
  std::vector<std::string> materials_;
  int unit_ = 0; ///< a mass unit 2^unit_ kg: 2^-62 of the heaviest a particle filling a cell can be
  std::vector<Sum> crossed_; ///< per material: signed mass crossed on this process, in units
  std::vector<Sum> sampled_; ///< every process's total at the previous row (rank 0's)
};

} // namespace talus
