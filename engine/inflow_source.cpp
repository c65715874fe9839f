#include "engine/inflow_source.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace talus {

InflowSource::InflowSource(InflowSpec spec) : spec_(std::move(spec)) {
  const auto& s = spec_;
  if (s.time.size() < 2 || s.discharge.size() != s.time.size() || s.speed.size() != s.time.size())
    throw std::invalid_argument("a hydrograph needs two rows at least, each with time, discharge and speed");
  for (size_t i = 0; i < s.time.size(); ++i) {
    if (i && !(s.time[i] > s.time[i - 1])) throw std::invalid_argument("the hydrograph's times must increase");
    if (!(s.discharge[i] >= 0)) throw std::invalid_argument("the hydrograph's discharge must be >= 0");
    if (!(s.speed[i] > 0)) throw std::invalid_argument("the hydrograph's speed must be > 0");
  }
  if (!(s.spacing > 0) || s.ground.empty()) throw std::invalid_argument("the section is shorter than a particle spacing");
}

double InflowSource::discharge(double t) const {
  const auto& T = spec_.time;
  if (t <= T.front() || t >= T.back()) return 0.0;
  const size_t i = size_t(std::upper_bound(T.begin(), T.end(), t) - T.begin()) - 1;
  const double f = (t - T[i]) / (T[i + 1] - T[i]);
  return spec_.discharge[i] + f * (spec_.discharge[i + 1] - spec_.discharge[i]);
}

double InflowSource::speed(double t) const {
  const auto& T = spec_.time;
  if (t <= T.front()) return spec_.speed.front();
  if (t >= T.back()) return spec_.speed.back();
  const size_t i = size_t(std::upper_bound(T.begin(), T.end(), t) - T.begin()) - 1;
  const double f = (t - T[i]) / (T[i + 1] - T[i]);
  return spec_.speed[i] + f * (spec_.speed[i + 1] - spec_.speed[i]);
}

double InflowSource::hydrographVolume(double t) const {
  // Exact integral of the piecewise-linear Q: trapezoids, the last one cut at t.
  const auto& T = spec_.time;
  const auto& Q = spec_.discharge;
  double v = 0;
  for (size_t i = 0; i + 1 < T.size() && T[i] < t; ++i) {
    const double t1 = std::min(t, T[i + 1]);
    const double q1 = Q[i] + (t1 - T[i]) / (T[i + 1] - T[i]) * (Q[i + 1] - Q[i]);
    v += 0.5 * (Q[i] + q1) * (t1 - T[i]);
  }
  return v;
}

size_t InflowSource::emit(const SparseGrid&, double time, double dt, const std::vector<MaterialGroup*>& groups) {
  pending_ += hydrographVolume(time) - hydrographVolume(time - dt);
  const double v = speed(time), s = spec_.spacing;
  cursor_ += v * dt;
  size_t made = 0;
  while (cursor_ >= s) {
    cursor_ -= s;
    if (!(pending_ > 0)) continue;
    const double q = discharge(time), width = double(slots()) * s;
    const double h = q > 0 ? q / (v * width) : s; // the layer's thickness now
    const int layers = std::max(1, int(std::lround(h / s)));
    const double m = spec_.density * pending_ / double(slots() * size_t(layers));
    const Vec3d along = (spec_.b - spec_.a).normalized();
    ParticleSet& P = groups[size_t(spec_.group)]->particles;
    for (size_t k = 0; k < slots(); ++k) {
      const Vec3d base = spec_.a + (double(k) + 0.5) * s * along + (cursor_ + 0.5 * s) * spec_.direction;
      for (int l = 0; l < layers; ++l) {
        P.x.push_back(Vec3d(base.x(), base.y(), spec_.ground[k] + (l + 0.5) * h / layers).cast<Real>());
        P.v.push_back((v * spec_.direction).cast<Real>());
        P.mass.push_back(Real(m));
        ++made;
      }
    }
    P.C.resize(P.x.size(), Mat3::Zero());
    P.tau.resize(P.x.size(), Sym3{});
    groups[size_t(spec_.group)]->resizeState(P.size());
    emitted_ += pending_;
    pending_ = 0;
  }
  return made;
}

void InflowSource::save(StateArchive& a, const std::string& prefix) const {
  a.putVector(prefix + "state", std::vector<double>{pending_, cursor_, emitted_});
}

void InflowSource::load(const StateArchive& a, const std::string& prefix) {
  std::vector<double> s;
  a.getVector(prefix + "state", s);
  if (s.size() != 3) throw std::runtime_error("checkpoint's inflow '" + spec_.name + "' does not fit the scene's");
  pending_ = s[0], cursor_ = s[1], emitted_ = s[2];
}

} // namespace talus
