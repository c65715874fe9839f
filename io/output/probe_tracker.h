// A point that moves with the flow ([[output.probes]]): the "point P0 on the slide" of a
// displacement-rate history.
//
// The probe starts at a world point and is advected like a material point: after every step it
// moves by dt times the mass-weighted mean velocity of the particles (of the listed materials)
// within `radius` of it. Particles carry no identity through the engine's reordering, so this
// interpolated velocity is what follows a piece of material. Its columns in series.csv are the
// speed of that mean velocity and the probe's world position; once no particle lies within the
// radius the probe stops and its speed is NaN. The sums (mass, momentum, mass times height) are
// fixed-point integers (io/output/step_parts.h): under ranks every process sends its own every
// step to every process, and each moves its copy of the probe alike (Reads::Shared).
#pragma once

#include "io/output/output_settings.h"
#include "io/output/series_columns.h"

namespace talus {

class ProbeTracker final : public SeriesColumns {
public:
  /// A probe without a radius uses two grid cells.
  explicit ProbeTracker(ProbeSpec spec);

  /// From every particle: the start point's height for an [x, y] probe, and its first velocity.
  /// @throw std::runtime_error when no particle of its materials is within its radius
  void onStart(const Simulation& sim) override;
  /// On a process other than rank 0: what sharedPart needs; the place comes with takeState.
  void prepareParts(const Simulation& local) override;
  std::vector<std::string> header() const override;
  Reads reads() const override { return Reads::Shared; }
  void sharedPart(const Simulation& local, const PartBounds& b, std::vector<char>& out) const override;
  void sharedStep(const Simulation& sim, double dt, const PartBounds& b, const std::vector<std::string_view>& parts) override;
  void sample(const Simulation& sim, double elapsed, std::vector<double>& row) override;
  void shareState(std::vector<char>& out) const override;
  /// @throw std::runtime_error if `in` is not what shareState writes
  void takeState(std::string_view in) override;
  /// The probe's place and last velocity: a resumed run's outputs start from the scene's initial
  /// state (onStart), where the probe is back at its start point.
  void save(StateArchive& a, const std::string& prefix) const override;
  void load(const StateArchive& a, const std::string& prefix) override;

  /// World position of the probe and the mean velocity found there at the last update.
  Vec3d position() const { return local_ + origin_; }
  Vec3d velocity() const { return velocity_; }
  bool lost() const { return lost_; }

private:
  /// Mass-weighted mean velocity of the selected particles within the radius of `at` (local)
  /// from every process's sums (sumsAround); false when there is none. With `z`, also their
  /// mass-weighted mean height.
  bool meanVelocity(const Simulation& sim, const PartBounds& b, const std::vector<std::string_view>& parts, Vec3d& v,
                    double* z = nullptr) const;
  /// This process's sums around `at`: within the radius in xy only with `columnOnly`.
  void sumsAround(const Simulation& local, const PartBounds& b, const Vec3d& at, bool columnOnly, std::vector<char>& out) const;
  /// From every particle of `sim` alone (the start).
  bool meanVelocityOf(const Simulation& sim, const Vec3d& at, bool columnOnly, Vec3d& v, double* z = nullptr) const;

  ProbeSpec spec_;
  double radius_;
  std::vector<uint8_t> use_; ///< per material group
  Vec3d origin_ = Vec3d::Zero(), local_ = Vec3d::Zero(), velocity_ = Vec3d::Zero();
  bool lost_ = false;
};

} // namespace talus
