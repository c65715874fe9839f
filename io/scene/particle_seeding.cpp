#include "io/scene/particle_seeding.h"

#include "io/common/resource_limits.h"

#include <string>

#include <cmath>
#include <tbb/parallel_for.h>

namespace talus {

namespace {
uint64_t splitmix(uint64_t x) {
  x += 0x9e3779b97f4a7c15ull;
  x = (x ^ (x >> 30)) * 0xbf58476d1ce4e5b9ull;
  x = (x ^ (x >> 27)) * 0x94d049bb133111ebull;
  return x ^ (x >> 31);
}
double unit(uint64_t& state) { // uniform in [0, 1)
  state = splitmix(state);
  return double(state >> 11) * (1.0 / 9007199254740992.0);
}
int cubeRoot(int n) {
  const int r = int(std::lround(std::cbrt(double(n))));
  return r * r * r == n ? r : 0;
}
bool insideSolid(const SeedSpec& spec, const Vec3d& x) {
  if (spec.terrain && spec.terrain->distance(x) < 0) return true;
  for (const Sdf* s : spec.solids)
    if (s->distance(x) < 0) return true;
  return false;
}
} // namespace

Vec3d cellSample(const SeedSpec& spec, int64_t i, int64_t j, int64_t k, int s, bool jittered) {
  uint64_t h = splitmix(spec.seed ^ splitmix(uint64_t(i) * 73856093ull ^ splitmix(uint64_t(j) * 19349663ull ^
                                                                           splitmix(uint64_t(k) * 83492791ull))));
  h = splitmix(h + uint64_t(s));
  const int n = cubeRoot(spec.particlesPerCell);
  if (n > 0) {
    const int a = s / (n * n), b = (s / n) % n, c = s % n;
    Vec3d p((a + 0.5) / n, (b + 0.5) / n, (c + 0.5) / n);
    if (spec.jitter > 0 && jittered)
      for (int d = 0; d < 3; ++d) {
        const double u = unit(h); // drawn for every axis, so z's draw is the same either way
        if (d == 2 || !spec.verticalJitter) p[d] += (u - 0.5) * spec.jitter / n;
      }
    return p;
  }
  // Stratify along x so samples never cluster in one half of the cell.
  const double ppc = spec.particlesPerCell;
  return {(s + unit(h)) / ppc, unit(h), unit(h)};
}

namespace {

/// The seeded positions of grid column (i, j), cells k0 .. k1 - 1, in (cell, sample) order, into
/// `out`. With spec.latticeDecides (a lattice with jitter) a sample is kept when its lattice point
/// is inside, at its jittered place where that stays inside, else at the lattice point: every
/// lattice column keeps the lattice's count, so a layer's mass per plan area is uniform, and the
/// count is the lattice's unbiased estimate of the volume.
void columnSamples(const SeedSpec& spec, int64_t i, int64_t j, int64_t k0, int64_t k1,
                   const std::function<bool(const Vec3d&)>& keeps, std::vector<Vec3d>& out) {
  out.clear();
  const bool lattice = spec.latticeDecides && cubeRoot(spec.particlesPerCell) > 0 && spec.jitter > 0;
  for (int64_t k = k0; k < k1; ++k)
    for (int s = 0; s < spec.particlesPerCell; ++s) {
      const Vec3d cell = Vec3d(double(i), double(j), double(k));
      const Vec3d x = (cell + cellSample(spec, i, j, k, s)) * spec.dx;
      if (!lattice) {
        if (keeps(x)) out.push_back(x);
        continue;
      }
      const Vec3d x0 = (cell + cellSample(spec, i, j, k, s, false)) * spec.dx;
      if (keeps(x0)) out.push_back(keeps(x) ? x : x0);
    }
}

} // namespace

size_t seedRegion(const Vec3d& lo, const Vec3d& hi, const std::function<bool(const Vec3d&)>& inside,
                  const std::function<Vec3d(const Vec3d&)>& velocity, const SeedSpec& spec,
                  MaterialGroup& group, const Mat3d& velocityGradient) {
  double candidates = spec.particlesPerCell;
  for (int d = 0; d < 3; ++d) candidates *= std::ceil(hi[d] / spec.dx) - std::floor(lo[d] / spec.dx);
  if (candidates > spec.maxParticles)
    throw InputError("", "would test " + std::to_string(candidates) + " particle positions, more than max_particles = " +
                             std::to_string(spec.maxParticles) + " (is dx too small?)");
  // Every column spans the whole box.
  const ColumnRange whole = [&](double, double, double, double, double& zlo, double& zhi) {
    zlo = lo.z(), zhi = hi.z();
    return true;
  };
  return seedColumns(lo, hi, whole, inside, velocity, spec, group, velocityGradient);
}

size_t seedColumns(const Vec3d& lo, const Vec3d& hi, const ColumnRange& columnRange,
                   const std::function<bool(const Vec3d&)>& inside,
                   const std::function<Vec3d(const Vec3d&)>& velocity, const SeedSpec& spec, MaterialGroup& group,
                   const Mat3d& velocityGradient) {
  const Mat3 C0 = velocityGradient.cast<Real>();
  const double dx = spec.dx;
  const Real mass = Real(group.density() * dx * dx * dx / spec.particlesPerCell);
  int64_t c0[2], c1[2];
  for (int d = 0; d < 2; ++d) {
    c0[d] = int64_t(std::floor(lo[d] / dx));
    c1[d] = int64_t(std::ceil(hi[d] / dx));
  }
  const size_t rows = size_t(std::max<int64_t>(0, c1[0] - c0[0]));
  const double columns = double(rows) * double(std::max<int64_t>(0, c1[1] - c0[1]));
  if (columns * spec.particlesPerCell > spec.maxParticles)
    throw InputError("", "would seed at least " + std::to_string(columns * spec.particlesPerCell) +
                             " particles, more than max_particles = " + std::to_string(spec.maxParticles) +
                             " (is dx too small?)");
  // Per x-row of columns: positions and velocities, concatenated in row order afterwards. Under
  // MPI ranks every row is counted and this rank's rows kept.
  std::vector<std::vector<Vec3>> xs(rows), vs(rows);
  std::vector<size_t> counts(rows, 0);
  std::vector<std::vector<uint32_t>> ordinal(rows); // kept particles' places in their row
  SeedSlice* slice = spec.slice && spec.slice->active() ? spec.slice : nullptr;
  auto keeps = [&](const Vec3d& x) {
    return !(x.array() < lo.array()).any() && !(x.array() > hi.array()).any() && inside(x) && !insideSolid(spec, x);
  };
  tbb::parallel_for(size_t(0), rows, [&](size_t r) {
    const int64_t i = c0[0] + int64_t(r);
    std::vector<Vec3d> kept;
    for (int64_t j = c0[1]; j < c1[1]; ++j) {
      double zlo, zhi;
      if (!columnRange(double(i) * dx, double(j) * dx, double(i + 1) * dx, double(j + 1) * dx, zlo, zhi)) continue;
      const int64_t k0 = int64_t(std::floor(std::max(zlo, lo.z()) / dx));
      const int64_t k1 = int64_t(std::ceil(std::min(zhi, hi.z()) / dx));
      columnSamples(spec, i, j, k0, k1, keeps, kept);
      for (const Vec3d& x : kept) {
        ++counts[r];
        if (slice) {
          // By the x column of the stored (float) position, the column the hydrostatic start
          // keys it by: a sample within rounding of a cell edge goes with that column.
          if (!slice->keeps(int64_t(std::floor(double(Real(x.x())) / dx)))) continue;
          ordinal[r].push_back(uint32_t(counts[r] - 1));
        }
        xs[r].push_back(x.cast<Real>());
        vs[r].push_back(velocity(x).cast<Real>());
      }
    }
  });
  ParticleSet& P = group.particles;
  size_t total = P.size(), all = 0;
  for (size_t r = 0; r < rows; ++r) total += xs[r].size(), all += counts[r];
  if (slice) {
    // One process's index of every kept particle: its group's earlier particles, then the rows.
    const size_t g = size_t(group.index());
    if (slice->seeded.size() <= g) slice->seeded.resize(g + 1, 0), slice->index.resize(g + 1);
    uint64_t at = slice->seeded[g];
    for (size_t r = 0; r < rows; ++r) {
      for (uint32_t k : ordinal[r]) slice->index[g].push_back(at + k);
      at += counts[r];
    }
    slice->seeded[g] = at;
  }
  P.x.reserve(total), P.v.reserve(total), P.C.reserve(total), P.tau.reserve(total), P.mass.reserve(total);
  for (size_t r = 0; r < rows; ++r) {
    P.x.insert(P.x.end(), xs[r].begin(), xs[r].end());
    P.v.insert(P.v.end(), vs[r].begin(), vs[r].end());
  }
  P.C.resize(total, C0);
  P.tau.resize(total, Sym3{});
  P.mass.resize(total, mass);
  group.resizeState(P.size());
  return all;
}

} // namespace talus
