// A point that moves with the flow ([[output.probes]]): the "point P0 on the slide" of a
// displacement-rate history.
//
// The probe starts at a world point and is advected like a material point: after every step it
// moves by dt times the mass-weighted mean velocity of the particles (of the listed materials)
// within `radius` of it. Particles carry no identity through the engine's reordering, so this
// interpolated velocity is what follows a piece of material. Its columns in series.csv are the
// speed of that mean velocity and the probe's world position; once no particle lies within the
// radius the probe stops and its speed is NaN.
#pragma once

#include "io/output/output_settings.h"
#include "io/output/series_columns.h"

namespace talus {

class ProbeTracker final : public SeriesColumns {
public:
  /// A probe without a radius uses two grid cells.
  explicit ProbeTracker(ProbeSpec spec);

  void onStart(const Simulation& sim) override;
  std::vector<std::string> header() const override;
  void onStep(const Simulation& sim, double dt) override;
  void sample(const Simulation& sim, double elapsed, std::vector<double>& row) override;
  /// The probe's place and last velocity: a resumed run's outputs start from the scene's initial
  /// state (onStart), where the probe is back at its start point.
  void save(StateArchive& a, const std::string& prefix) const override;
  void load(const StateArchive& a, const std::string& prefix) override;

  /// World position of the probe and the mean velocity found there at the last update.
  Vec3d position() const { return local_ + origin_; }
  Vec3d velocity() const { return velocity_; }
  bool lost() const { return lost_; }

private:
  /// Mass-weighted mean velocity of the selected particles within the radius of `at` (local);
  /// false when there is none. `columnOnly` measures within the radius in xy only and also
  /// returns their mass-weighted mean height in `z`.
  bool meanVelocity(const Simulation& sim, const Vec3d& at, bool columnOnly, Vec3d& v, double* z = nullptr) const;

  ProbeSpec spec_;
  double radius_;
  std::vector<uint8_t> use_; ///< per material group
  Vec3d origin_ = Vec3d::Zero(), local_ = Vec3d::Zero(), velocity_ = Vec3d::Zero();
  bool lost_ = false;
};

} // namespace talus
