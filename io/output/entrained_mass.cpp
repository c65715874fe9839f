#include "io/output/entrained_mass.h"

#include <algorithm>
#include <cmath>

namespace talus {

void EntrainedMassColumns::onStart(const Simulation& sim) {
  groups_.clear(), groupNames_.clear(), start_.clear();
  for (size_t g = 0; g < sim.groups().size(); ++g)
    if (std::find(names_.begin(), names_.end(), sim.groups()[g]->name()) != names_.end()) {
      groups_.push_back(int(g));
      groupNames_.push_back(sim.groups()[g]->name());
      start_.push_back(volumes(sim, int(g)));
    }
}

std::vector<std::string> EntrainedMassColumns::header() const {
  std::vector<std::string> h;
  for (const std::string& n : groupNames_) h.push_back("entrained_mass_kg_" + safeName(n));
  return h;
}

EntrainedMassColumns::Columns EntrainedMassColumns::volumes(const Simulation& sim, int g) const {
  const MaterialGroup& grp = *sim.groups()[size_t(g)];
  const double inv = 1.0 / sim.settings().dx, perKg = 1.0 / grp.density();
  Columns c;
  const ParticleSet& P = grp.particles;
  for (size_t p = 0; p < P.size(); ++p) {
    const double fx = double(P.x[p][0]) * inv, fy = double(P.x[p][1]) * inv;
    const int32_t i = int32_t(std::floor(fx)), j = int32_t(std::floor(fy));
    const double tx = fx - i, ty = fy - j, v = double(P.mass[p]) * perKg;
    auto add = [&](int32_t a, int32_t b, double w) {
      if (w > 0) c[(uint64_t(uint32_t(a)) << 32) | uint32_t(b)] += w * v;
    };
    add(i, j, (1 - tx) * (1 - ty)), add(i + 1, j, tx * (1 - ty)), add(i, j + 1, (1 - tx) * ty), add(i + 1, j + 1, tx * ty);
  }
  return c;
}

void EntrainedMassColumns::sample(const Simulation& sim, double, std::vector<double>& row) {
  for (size_t k = 0; k < groups_.size(); ++k) {
    const Columns now = volumes(sim, groups_[k]);
    // Summed in key order: the same total whatever the hash map's iteration order.
    std::vector<std::pair<uint64_t, double>> lost;
    for (const auto& [key, v0] : start_[k]) {
      const auto it = now.find(key);
      const double v = it == now.end() ? 0.0 : it->second;
      if (v0 > v) lost.push_back({key, v0 - v});
    }
    std::sort(lost.begin(), lost.end());
    double sum = 0;
    for (const auto& l : lost) sum += l.second;
    row.push_back(sum * sim.groups()[size_t(groups_[k])]->density());
  }
}

} // namespace talus
