#include "io/output/section_discharge.h"

#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

namespace talus {

void SectionDischarge::onStart(const Simulation& sim) {
  const Vec3d o = sim.settings().origin;
  local_.clear();
  for (const auto& p : spec_.points) local_.push_back(p - o.head<2>());
  lo_ = hi_ = local_[0];
  for (const auto& p : local_) lo_ = lo_.cwiseMin(p), hi_ = hi_.cwiseMax(p);
  zMin_ = spec_.zMin - o.z();
  zMax_ = spec_.zMax - o.z();
  materials_.clear();
  for (const auto* g : sim.groups()) materials_.push_back(g->name());
  volume_.assign(materials_.size(), 0.0);
}

std::vector<std::string> SectionDischarge::header() const {
  std::vector<std::string> h;
  for (const auto& m : materials_) h.push_back("discharge_m3_s_" + spec_.name + "_" + safeName(m));
  if (materials_.size() > 1) h.push_back("discharge_m3_s_" + spec_.name + "_total");
  return h;
}

void SectionDischarge::onStep(const Simulation& sim, double dt) {
  const auto& groups = sim.groups();
  const size_t nseg = local_.size() - 1;
  for (size_t g = 0; g < groups.size(); ++g) {
    const ParticleSet& P = groups[g]->particles;
    // Deterministic reduction: the same sum whatever the thread count.
    const double crossed = tbb::parallel_deterministic_reduce(
        tbb::blocked_range<size_t>(0, P.size(), 4096), 0.0,
        [&](const tbb::blocked_range<size_t>& r, double acc) {
          for (size_t p = r.begin(); p != r.end(); ++p) {
            const Eigen::Vector2d p1(P.x[p][0], P.x[p][1]);
            const Eigen::Vector2d p0 = p1 - dt * Eigen::Vector2d(P.v[p][0], P.v[p][1]);
            if ((p0.x() < lo_.x() && p1.x() < lo_.x()) || (p0.x() > hi_.x() && p1.x() > hi_.x()) ||
                (p0.y() < lo_.y() && p1.y() < lo_.y()) || (p0.y() > hi_.y() && p1.y() > hi_.y()))
              continue;
            const double z1 = P.x[p][2], z0 = z1 - dt * double(P.v[p][2]);
            int sign = 0;
            for (size_t k = 0; k < nseg; ++k) { // every crossing counts: a zig-zag may be crossed twice
              const Eigen::Vector2d a = local_[k], d = local_[k + 1] - a;
              const double s0 = d.x() * (p0.y() - a.y()) - d.y() * (p0.x() - a.x());
              const double s1 = d.x() * (p1.y() - a.y()) - d.y() * (p1.x() - a.x());
              // Sides are half-open (s > 0 is left), so a particle on the line is counted once.
              if ((s0 > 0) == (s1 > 0)) continue;
              const double t = s0 / (s0 - s1);
              const double u = (p0 + t * (p1 - p0) - a).dot(d) / d.squaredNorm();
              const bool last = k + 1 == nseg;
              if (u < 0 || u > 1 || (u == 1 && !last)) continue;
              const double z = z0 + t * (z1 - z0);
              if (z < zMin_ || z >= zMax_) continue;
              sign += s1 > 0 ? 1 : -1; // right -> left is positive
            }
            if (sign) acc += sign * double(P.mass[p]);
          }
          return acc;
        },
        std::plus<double>());
    volume_[g] += crossed / groups[g]->density();
  }
}

void SectionDischarge::sample(const Simulation&, double elapsed, std::vector<double>& row) {
  double total = 0;
  for (double& v : volume_) {
    row.push_back(elapsed > 0 ? v / elapsed : 0.0);
    total += elapsed > 0 ? v / elapsed : 0.0;
    v = 0;
  }
  if (volume_.size() > 1) row.push_back(total);
}

} // namespace talus
