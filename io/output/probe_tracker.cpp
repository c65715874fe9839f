#include "io/output/probe_tracker.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

namespace talus {

ProbeTracker::ProbeTracker(ProbeSpec spec) : spec_(std::move(spec)), radius_(spec_.radius) {}

std::vector<std::string> ProbeTracker::header() const {
  const std::string& n = spec_.name;
  return {"probe_speed_m_s_" + n, "probe_x_m_" + n, "probe_y_m_" + n, "probe_z_m_" + n};
}

namespace {

/// The units of a probe's sums: mass, momentum (per component) and mass times height, each
/// particle's value below 2^62 units, summed in 128 bits.
struct Units {
  int m, p, z;
  explicit Units(const PartBounds& b)
      : m(unitExponent(b.maxMass, kTotalBits)), p(unitExponent(b.maxMass * std::sqrt(b.maxSpeed2), kTotalBits)),
        z(unitExponent(b.maxMass * b.maxCoord, kTotalBits)) {}
};

struct Sums {
  __int128 v[5] = {0, 0, 0, 0, 0}; ///< mass, momentum x y z, mass times height
  Sums& operator+=(const Sums& o) {
    for (int k = 0; k < 5; ++k) v[k] += o.v[k];
    return *this;
  }
};

} // namespace

void ProbeTracker::sumsAround(const Simulation& local, const PartBounds& b, const Vec3d& at, bool columnOnly,
                              std::vector<char>& out) const {
  const Units u(b);
  const double perM = powerOfTwo(-u.m), perP = powerOfTwo(-u.p), perZ = powerOfTwo(-u.z);
  const double r2 = radius_ * radius_;
  Sums total;
  const auto& groups = local.groups();
  for (size_t g = 0; g < groups.size(); ++g) {
    if (!use_[g]) continue;
    const ParticleSet& P = groups[g]->particles;
    // Whole units: the same sums in any order, so at any thread and rank count.
    total += tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, P.size(), 8192), Sums{},
        [&](const tbb::blocked_range<size_t>& r, Sums acc) {
          for (size_t p = r.begin(); p != r.end(); ++p) {
            const Vec3d d = P.x[p].cast<double>() - at;
            const double d2 = columnOnly ? d.head<2>().squaredNorm() : d.squaredNorm();
            if (d2 > r2) continue;
            const double m = double(P.mass[p]);
            acc.v[0] += toUnits(m, perM);
            for (int k = 0; k < 3; ++k) acc.v[1 + k] += toUnits(m * double(P.v[p][k]), perP);
            acc.v[4] += toUnits(m * double(P.x[p][2]), perZ);
          }
          return acc;
        },
        [](Sums a, const Sums& c) { return a += c; });
  }
  PartWriter put(out);
  for (const __int128& v : total.v) put.put(v);
}

bool ProbeTracker::meanVelocity(const Simulation&, const PartBounds& b, const std::vector<std::string_view>& parts,
                                Vec3d& v, double* z) const {
  Sums total;
  for (const auto& p : parts) {
    PartReader get(p);
    for (__int128& t : total.v) t += get.get<__int128>();
  }
  if (total.v[0] <= 0) return false;
  const Units u(b);
  const double m = double(total.v[0]) * powerOfTwo(u.m);
  for (int k = 0; k < 3; ++k) v[k] = double(total.v[1 + k]) * powerOfTwo(u.p) / m;
  if (z) *z = double(total.v[4]) * powerOfTwo(u.z) / m;
  return true;
}

bool ProbeTracker::meanVelocityOf(const Simulation& sim, const Vec3d& at, bool columnOnly, Vec3d& v, double* z) const {
  std::vector<char> own;
  const PartBounds b = PartBounds::of(sim);
  sumsAround(sim, b, at, columnOnly, own);
  return meanVelocity(sim, b, {std::string_view(own.data(), own.size())}, v, z);
}

void ProbeTracker::prepareParts(const Simulation& local) {
  radius_ = spec_.radius > 0 ? spec_.radius : 2 * local.settings().dx;
  const auto& groups = local.groups();
  use_.assign(groups.size(), spec_.materials.empty() ? 1 : 0);
  for (size_t g = 0; g < groups.size(); ++g)
    for (const auto& n : spec_.materials)
      if (groups[g]->name() == n) use_[g] = 1;
  origin_ = local.settings().origin;
  local_ = spec_.point - origin_;
  lost_ = false;
  velocity_.setZero();
}

void ProbeTracker::onStart(const Simulation& sim) {
  prepareParts(sim);
  if (!spec_.hasZ) {
    // [x, y]: start at the mass-weighted mean height of the material in that column.
    double z = 0;
    if (!meanVelocityOf(sim, Vec3d(local_.x(), local_.y(), 0), true, velocity_, &z))
      throw std::runtime_error("probe '" + spec_.name + "': no particle of its materials within " +
                               std::to_string(radius_) + " m of its point (in x and y)");
    local_.z() = z;
  }
  if (!meanVelocityOf(sim, local_, false, velocity_)) {
    if (spec_.hasZ)
      throw std::runtime_error("probe '" + spec_.name + "': no particle of its materials within " +
                               std::to_string(radius_) + " m of its point");
    lost_ = true;
  }
}

void ProbeTracker::sharedPart(const Simulation& local, const PartBounds& b, std::vector<char>& out) const {
  if (lost_) return; // every process has lost it alike
  sumsAround(local, b, local_, false, out);
}

void ProbeTracker::sharedStep(const Simulation& sim, double dt, const PartBounds& b,
                              const std::vector<std::string_view>& parts) {
  if (lost_) return;
  // As a particle: the velocity gathered at the old position, then x += dt v (the engine moved
  // the particles by dt times their new velocities).
  Vec3d v;
  if (!meanVelocity(sim, b, parts, v)) {
    lost_ = true;
    return;
  }
  velocity_ = v;
  local_ += dt * v;
}

void ProbeTracker::shareState(std::vector<char>& out) const {
  PartWriter put(out);
  for (int k = 0; k < 3; ++k) put.put(local_[k]), put.put(velocity_[k]);
  put.put(uint8_t(lost_));
}

void ProbeTracker::takeState(std::string_view in) {
  PartReader get(in);
  for (int k = 0; k < 3; ++k) local_[k] = get.get<double>(), velocity_[k] = get.get<double>();
  lost_ = get.get<uint8_t>() != 0;
  if (!get.done()) throw std::runtime_error("probe '" + spec_.name + "': rank 0's state is not a probe's");
}

void ProbeTracker::save(StateArchive& a, const std::string& prefix) const {
  a.putVector(prefix + "local", std::vector<double>{local_.x(), local_.y(), local_.z()});
  a.putVector(prefix + "velocity", std::vector<double>{velocity_.x(), velocity_.y(), velocity_.z()});
  a.putValue(prefix + "lost", int32_t(lost_));
}

void ProbeTracker::load(const StateArchive& a, const std::string& prefix) {
  std::vector<double> x, v;
  a.getVector(prefix + "local", x);
  a.getVector(prefix + "velocity", v);
  if (x.size() != 3 || v.size() != 3) throw std::runtime_error("checkpoint: probe '" + spec_.name + "' has no position");
  local_ = Vec3d(x[0], x[1], x[2]), velocity_ = Vec3d(v[0], v[1], v[2]);
  lost_ = a.getValue<int32_t>(prefix + "lost") != 0;
}

void ProbeTracker::sample(const Simulation&, double, std::vector<double>& row) {
  const Vec3d w = position();
  row.push_back(lost_ ? std::numeric_limits<double>::quiet_NaN() : velocity_.norm());
  row.push_back(w.x());
  row.push_back(w.y());
  row.push_back(w.z());
}

} // namespace talus
