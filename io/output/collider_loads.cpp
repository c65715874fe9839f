#include "io/output/collider_loads.h"

#include <cmath>
#include <cstdio>

namespace talus {

void ColliderLoadColumns::onStart(const Simulation& sim) {
  names_.clear();
  panels_.clear();
  const auto& st = sim.settings();
  for (const auto& c : sim.colliders()) {
    names_.push_back(safeName(c->name()));
    Panel p;
    if (c->isPanel())
      p.area = c->panelArea(st.dx, st.domain.min, st.domain.max), p.axis = c->faceAxis(), p.sign = c->faceUpper() ? 1 : -1;
    panels_.push_back(p);
  }
  acc_.assign(names_.size(), Acc{});
}

std::vector<std::string> ColliderLoadColumns::header() const {
  std::vector<std::string> h;
  for (size_t k = 0; k < names_.size(); ++k) {
    for (const char* q : {"force_x_N_", "force_y_N_", "force_z_N_", "force_N_", "max_force_N_", "moment_x_Nm_",
                          "moment_y_Nm_", "moment_z_Nm_"})
      h.push_back(q + names_[k]);
    if (panels_[k].area > 0) h.push_back("pressure_Pa_" + names_[k]), h.push_back("max_pressure_Pa_" + names_[k]);
  }
  return h;
}

void ColliderLoadColumns::onStep(const Simulation& sim, double dt) {
  const auto& loads = sim.colliderLoads();
  for (size_t k = 0; k < acc_.size() && k < loads.size(); ++k) {
    Acc& a = acc_[k];
    const ColliderLoad& l = loads[k];
    for (int d = 0; d < 3; ++d) a.impulse[d] += l.force[d] * dt, a.impulse[3 + d] += l.moment[d] * dt;
    const double f = l.force.norm();
    a.intervalMax = std::max(a.intervalMax, f);
    if (panels_[k].area > 0) a.intervalMaxNormal = std::max(a.intervalMaxNormal, panels_[k].sign * l.force[panels_[k].axis]);
    if (f > a.peak) {
      a.peak = f, a.peakTime = sim.time();
      for (int d = 0; d < 3; ++d) a.peakForce[d] = l.force[d];
    }
  }
}

void ColliderLoadColumns::sample(const Simulation&, double elapsed, std::vector<double>& row) {
  for (size_t k = 0; k < acc_.size(); ++k) {
    Acc& a = acc_[k];
    double m[6];
    for (int d = 0; d < 6; ++d) m[d] = elapsed > 0 ? a.impulse[d] / elapsed : 0.0;
    row.insert(row.end(), {m[0], m[1], m[2], std::sqrt(m[0] * m[0] + m[1] * m[1] + m[2] * m[2]), a.intervalMax, m[3],
                           m[4], m[5]});
    if (const Panel& p = panels_[k]; p.area > 0)
      row.insert(row.end(), {p.sign * m[p.axis] / p.area, a.intervalMaxNormal / p.area});
    for (double& i : a.impulse) i = 0;
    a.intervalMax = 0, a.intervalMaxNormal = 0;
  }
}

void ColliderLoadColumns::save(StateArchive& a, const std::string& prefix) const { a.putVector(prefix + "acc", acc_); }

void ColliderLoadColumns::load(const StateArchive& a, const std::string& prefix) {
  const size_t n = acc_.size();
  a.getVector(prefix + "acc", acc_);
  if (acc_.size() != n) throw std::runtime_error("checkpoint has loads of a different number of colliders");
}

std::string ColliderLoadColumns::summaryJson() const {
  std::string s = "{";
  char buf[256];
  for (size_t k = 0; k < acc_.size(); ++k) {
    const Acc& a = acc_[k];
    std::snprintf(buf, sizeof buf, "%s\"%s\": {\"peak_force_N\": %.10g, \"time_s\": %.10g, \"force_N\": [%.10g, %.10g, %.10g]}",
                  k ? ", " : "", names_[k].c_str(), a.peak, a.peakTime, a.peakForce[0], a.peakForce[1], a.peakForce[2]);
    s += buf;
  }
  return s + "}";
}

} // namespace talus
