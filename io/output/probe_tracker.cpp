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

bool ProbeTracker::meanVelocity(const Simulation& sim, const Vec3d& at, bool columnOnly, Vec3d& v, double* z) const {
  struct Sum {
    double m = 0, z = 0;
    Vec3d mv = Vec3d::Zero();
  };
  const double r2 = radius_ * radius_;
  Sum total;
  const auto& groups = sim.groups();
  for (size_t g = 0; g < groups.size(); ++g) {
    if (!use_[g]) continue;
    const ParticleSet& P = groups[g]->particles;
    // Fixed chunks summed in a fixed tree: the same probe path at any thread count.
    const Sum s = tbb::parallel_deterministic_reduce(
        tbb::blocked_range<size_t>(0, P.size(), 8192), Sum{},
        [&](const tbb::blocked_range<size_t>& r, Sum acc) {
          for (size_t p = r.begin(); p != r.end(); ++p) {
            const Vec3d d = P.x[p].cast<double>() - at;
            const double d2 = columnOnly ? d.head<2>().squaredNorm() : d.squaredNorm();
            if (d2 > r2) continue;
            const double m = double(P.mass[p]);
            acc.m += m;
            acc.mv += m * P.v[p].cast<double>();
            acc.z += m * double(P.x[p][2]);
          }
          return acc;
        },
        [](Sum a, const Sum& b) {
          a.m += b.m, a.mv += b.mv, a.z += b.z;
          return a;
        });
    total.m += s.m, total.mv += s.mv, total.z += s.z;
  }
  if (!(total.m > 0)) return false;
  v = total.mv / total.m;
  if (z) *z = total.z / total.m;
  return true;
}

void ProbeTracker::onStart(const Simulation& sim) {
  radius_ = spec_.radius > 0 ? spec_.radius : 2 * sim.settings().dx;
  const auto& groups = sim.groups();
  use_.assign(groups.size(), spec_.materials.empty() ? 1 : 0);
  for (size_t g = 0; g < groups.size(); ++g)
    for (const auto& n : spec_.materials)
      if (groups[g]->name() == n) use_[g] = 1;
  origin_ = sim.settings().origin;
  local_ = spec_.point - origin_;
  lost_ = false;
  velocity_.setZero();
  if (!spec_.hasZ) {
    // [x, y]: start at the mass-weighted mean height of the material in that column.
    double z = 0;
    if (!meanVelocity(sim, Vec3d(local_.x(), local_.y(), 0), true, velocity_, &z))
      throw std::runtime_error("probe '" + spec_.name + "': no particle of its materials within " +
                               std::to_string(radius_) + " m of its point (in x and y)");
    local_.z() = z;
  }
  if (!meanVelocity(sim, local_, false, velocity_)) {
    if (spec_.hasZ)
      throw std::runtime_error("probe '" + spec_.name + "': no particle of its materials within " +
                               std::to_string(radius_) + " m of its point");
    lost_ = true;
  }
}

void ProbeTracker::onStep(const Simulation& sim, double dt) {
  if (lost_) return;
  // As a particle: the velocity gathered at the old position, then x += dt v (the engine moved
  // the particles by dt times their new velocities).
  Vec3d v;
  if (!meanVelocity(sim, local_, false, v)) {
    lost_ = true;
    return;
  }
  velocity_ = v;
  local_ += dt * v;
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
