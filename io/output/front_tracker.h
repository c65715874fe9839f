// Flow front along a user path ([[output.paths]]): a polyline in world xy.
//
// At each row of series.csv the particles within the path's corridor are projected onto it and
// their volume (mass / reference density) is binned by distance along the path (bins of one grid
// cell, linear weights between neighbouring bins) and by lateral lane (one cell wide); a bin's
// thickness is its volume over its area. The front is the farthest distance along the path where
// a lane's thickness profile, interpolated linearly between bin centres, still reaches the
// threshold; its speed is the change since the previous row over the time between rows. The
// volumes are fixed-point integers (io/output/step_parts.h), so ranks bin their own particles. Only the
// path's materials count (all by default), and only particles at least min_speed fast, so a
// resting snow cover ahead of an avalanche is not taken for its front.
#pragma once

#include "io/common/polyline.h"
#include "io/output/output_settings.h"
#include "io/output/series_columns.h"

namespace talus {

class FrontTracker final : public PartsColumns {
public:
  /// `defaultThreshold` (m) applies when the path sets none (one particle spacing).
  FrontTracker(PathSpec spec, double defaultThreshold);

  void onStart(const Simulation& sim) override;
  std::vector<std::string> header() const override;
  /// In parts: each process's volumes per bin as fixed-point integers (dense, lanes × bins).
  void part(const Simulation& local, const PartBounds& b, std::vector<char>& out) const override;
  void sampleParts(const Simulation& sim, double elapsed, const PartBounds& b,
                   const std::vector<std::string_view>& parts, std::vector<double>& row) override;
  void save(StateArchive& a, const std::string& prefix) const override { a.putValue(prefix + "previous", previous_); }
  void load(const StateArchive& a, const std::string& prefix) override { previous_ = a.getValue<double>(prefix + "previous"); }

  /// Front position (m along the path from its first point), NaN when no bin reaches the
  /// threshold.
  double front(const Simulation& sim) const;
  double length() const { return path_.length(); }

private:
  int binsAlong() const;
  static int volumeUnit(const Simulation& sim, const PartBounds& b);
  double frontOf(const Simulation& sim, const PartBounds& b, const std::vector<std::string_view>& parts) const;
  PathSpec spec_;
  double threshold_;
  Polyline path_; ///< in the local frame
  double bin_ = 1;
  int lanes_ = 1;
  double previous_ = std::numeric_limits<double>::quiet_NaN();
};

} // namespace talus
