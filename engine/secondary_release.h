// Secondary releases: bodies held out of the run until the flow arrives over them, then released
// at rest (AvaFrame's SECREL/, a cascade's next slab: a snowpack that fails under the avalanche
// overrunning it). A held body is its particles (positions, masses) and a trigger: the flow's
// mass per plan area over any node column the body covers, above what that column held at the
// first step, reaching triggerMassPerArea (rho x the trigger thickness). Then its particles join
// their material group with zero velocity, and the body stays released.
//
// Checked after every step (the grid still holds the step's node masses); the cost is a pass over
// the nodes of the blocks above the held bodies, until they are released. One process only.
#pragma once

#include "engine/particle_source.h"

#include <string>
#include <unordered_map>
#include <vector>

namespace talus {

struct HeldBody {
  std::string name;
  int group = -1;                 ///< material group it joins
  std::vector<Vec3> x;            ///< particle positions (local frame)
  std::vector<Real> mass;         ///< particle masses
  double triggerMassPerArea = 0;  ///< kg/m2 of flow over a column that releases it
};

class SecondaryReleases final : public ParticleSource {
public:
  SecondaryReleases(std::vector<HeldBody> bodies, double dx);

  /// After a step ending at `time`: releases every held body whose trigger the grid's node masses
  /// reach. Returns the particles released.
  size_t emit(const SparseGrid& grid, double time, double dt, const std::vector<MaterialGroup*>& groups) override;

  const std::vector<HeldBody>& bodies() const { return bodies_; }
  /// When body b was released (s), or NaN while held.
  double releaseTime(size_t b) const { return released_[b]; }

  void save(StateArchive& a, const std::string& prefix) const override;
  void load(const StateArchive& a, const std::string& prefix) override;

private:

  std::vector<HeldBody> bodies_;
  double dx_;
  std::vector<double> released_;                               ///< per body: time, NaN while held
  std::vector<std::unordered_map<uint64_t, double>> baseline_; ///< per body: column -> mass at the first step
  std::vector<std::vector<uint64_t>> columns_;                 ///< per body: its node columns, sorted
  bool started_ = false;
};

} // namespace talus
