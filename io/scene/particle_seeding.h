// Filling regions with particles: particles_per_cell samples per grid cell, deterministic.
#pragma once

#include "engine/material_group.h"
#include "engine/sdf.h"

#include <functional>
#include <vector>

namespace talus {

/// Seeding split over MPI ranks. Rank `part` of `parts` keeps the particles whose positions lie in
/// its x-columns of cells (8 at a time, round robin, the same for every body, so a water column's
/// hydrostatic start sees all of it); every rank still visits every row, so counts, reports and
/// errors are the same on each. Per group (MaterialGroup::index()), `index` gets each kept particle's index in one
/// process's arrays, for Simulation::distribute.
struct SeedSlice {
  int part = 0, parts = 1;
  std::vector<uint64_t> seeded;             ///< one process's particle count so far, per group
  std::vector<std::vector<uint64_t>> index; ///< per group: the kept particles' indices
  bool active() const { return parts > 1; }
  bool keeps(int64_t row) const {
    const int64_t chunk = row >= 0 ? row / 8 : -((-row + 7) / 8);
    return int((chunk % parts + parts) % parts) == part;
  }
};

struct SeedSpec {
  double dx = 0.1;
  int particlesPerCell = 8;
  double jitter = 0;         ///< lattice jitter as a fraction of the sub-cell spacing, [0, 1]
  bool verticalJitter = false; ///< jitter along z only (lattice columns stay columns)
  bool latticeDecides = false; ///< a sample is seeded when its lattice point is inside (a uniform count per column)
  uint64_t seed = 0;
  const Sdf* terrain = nullptr; ///< samples inside the ground are skipped
  std::vector<const Sdf*> solids; ///< and inside these (structures)
  double maxParticles = 2e9;           ///< refuse (InputError) to seed more than this
  SeedSlice* slice = nullptr;          ///< under MPI ranks: keep this rank's rows only
};

/// Sample offsets inside a unit cell: a lattice when particles_per_cell is a cube (1, 8, 27...),
/// otherwise stratified random points; both hashed from (seed, cell, sample) so the result does
/// not depend on body order or thread count.
/// `jittered` false: the lattice point before the jitter (for a cube particles_per_cell).
Vec3d cellSample(const SeedSpec& spec, int64_t i, int64_t j, int64_t k, int s, bool jittered = true);

/// Appends particles for every sample in [lo, hi] (local frame) where `inside` holds.
/// Each particle gets volume dx^3 / ppc and mass density * volume, the velocity of `velocity`
/// and the APIC matrix C = velocityGradient (so a spinning body starts consistent). Returns the count.
size_t seedRegion(const Vec3d& lo, const Vec3d& hi, const std::function<bool(const Vec3d&)>& inside,
                  const std::function<Vec3d(const Vec3d&)>& velocity, const SeedSpec& spec,
                  MaterialGroup& group, const Mat3d& velocityGradient = Mat3d::Zero());

/// z-range of a body over the column of cells [x0, x1] x [y0, y1] (local frame); false when the
/// column holds none of it. May be conservative: `inside` decides each sample.
using ColumnRange = std::function<bool(double x0, double y0, double x1, double y1, double& zlo, double& zhi)>;

/// Both return one process's count (all rows) even when spec.slice keeps fewer.
/// seedRegion for bodies lying on terrain: the same samples, masses and rules, but only the
/// cells of each column that overlap its `columnRange` are visited, so a thin layer over a
/// kilometre of relief costs what its volume costs. Columns are seeded in parallel (`inside`,
/// `velocity` and spec.terrain must be thread-safe) and appended in a fixed order, so the
/// result does not depend on the thread count.
size_t seedColumns(const Vec3d& lo, const Vec3d& hi, const ColumnRange& columnRange,
                   const std::function<bool(const Vec3d&)>& inside,
                   const std::function<Vec3d(const Vec3d&)>& velocity, const SeedSpec& spec, MaterialGroup& group,
                   const Mat3d& velocityGradient = Mat3d::Zero());

} // namespace talus
