#include "io/output/section_discharge.h"

#include <algorithm>
#include <stdexcept>
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
  // The unit is the run's, not a step's (the totals add up over steps), fixed by the scene alone
  // so every process and a resumed run count alike; 128 bits leave room for 2^65 such particles.
  double heaviest = 0;
  for (const auto* g : sim.groups()) heaviest = std::max(heaviest, g->density());
  const double dx = sim.settings().dx;
  unit_ = unitExponent(heaviest * dx * dx * dx, kTotalBits);
  crossed_.assign(materials_.size(), 0);
  sampled_.assign(materials_.size(), 0);
}

std::vector<std::string> SectionDischarge::header() const {
  std::vector<std::string> h;
  for (const auto& m : materials_) h.push_back("discharge_m3_s_" + spec_.name + "_" + safeName(m));
  if (materials_.size() > 1) h.push_back("discharge_m3_s_" + spec_.name + "_total");
  return h;
}

void SectionDischarge::stepLocal(const Simulation& local, double dt) {
  const auto& groups = local.groups();
  const double perUnit = powerOfTwo(-unit_);
  const size_t nseg = local_.size() - 1;
  for (size_t g = 0; g < groups.size(); ++g) {
    const ParticleSet& P = groups[g]->particles;
    // Whole units: the same sum in any order, so at any thread and rank count.
    crossed_[g] += tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, P.size(), 4096), Sum(0),
        [&](const tbb::blocked_range<size_t>& r, Sum acc) {
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
            if (sign) acc += sign * Sum(double(P.mass[p]) * perUnit);
          }
          return acc;
        },
        std::plus<Sum>());
  }
}

void SectionDischarge::part(const Simulation&, const PartBounds&, std::vector<char>& out) const {
  putTotals(out); // whatever the bounds: their unit is the run's
}

void SectionDischarge::putTotals(std::vector<char>& out) const {
  PartWriter put(out);
  for (Sum c : crossed_) put.put(c);
}

void SectionDischarge::sampleParts(const Simulation& sim, double elapsed, const PartBounds&,
                                   const std::vector<std::string_view>& parts, std::vector<double>& row) {
  std::vector<Sum> total(crossed_.size(), 0);
  for (const auto& p : parts) {
    PartReader get(p);
    for (Sum& t : total) t += get.get<Sum>();
  }
  double sum = 0;
  for (size_t g = 0; g < total.size(); ++g) {
    const double volume = double(total[g] - sampled_[g]) * powerOfTwo(unit_) / sim.groups()[g]->density();
    const double q = elapsed > 0 ? volume / elapsed : 0.0;
    row.push_back(q), sum += q;
  }
  if (total.size() > 1) row.push_back(sum);
  sampled_ = total;
}

void SectionDischarge::handOver(std::vector<char>& out) {
  putTotals(out);
  std::fill(crossed_.begin(), crossed_.end(), 0);
}

void SectionDischarge::takeOver(std::string_view in) {
  PartReader get(in);
  for (Sum& c : crossed_) c += get.get<Sum>();
  if (!get.done()) throw std::runtime_error("section '" + spec_.name + "': another rank's totals hold other materials");
}

void SectionDischarge::save(StateArchive& a, const std::string& prefix) const {
  a.putVector(prefix + "crossed", crossed_);
  a.putVector(prefix + "sampled", sampled_);
}

void SectionDischarge::load(const StateArchive& a, const std::string& prefix) {
  a.getVector(prefix + "crossed", crossed_);
  a.getVector(prefix + "sampled", sampled_);
  if (crossed_.size() != materials_.size() || sampled_.size() != materials_.size())
    throw std::runtime_error("checkpoint: section '" + spec_.name + "' has other materials than the scene");
}

} // namespace talus
