#include "io/output/entrained_mass.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace talus {

void EntrainedMassColumns::prepareParts(const Simulation& local) {
  groups_.clear(), groupNames_.clear();
  for (size_t g = 0; g < local.groups().size(); ++g)
    if (std::find(names_.begin(), names_.end(), local.groups()[g]->name()) != names_.end()) {
      groups_.push_back(int(g));
      groupNames_.push_back(local.groups()[g]->name());
    }
}

void EntrainedMassColumns::onStart(const Simulation& sim) {
  prepareParts(sim);
  // Through a part, as every later sample: the start as one process has it.
  std::vector<char> own;
  const PartBounds b = PartBounds::of(sim);
  part(sim, b, own);
  start_ = volumesFrom(sim, b, {std::string_view(own.data(), own.size())});
}

std::vector<std::string> EntrainedMassColumns::header() const {
  std::vector<std::string> h;
  for (const std::string& n : groupNames_) h.push_back("entrained_mass_kg_" + safeName(n));
  return h;
}

int EntrainedMassColumns::unit(const Simulation& sim, const PartBounds& b) {
  return unitExponent(volumeBound(sim, b), kCellBits);
}

void EntrainedMassColumns::part(const Simulation& local, const PartBounds& b, std::vector<char>& out) const {
  const double inv = 1.0 / local.settings().dx, perUnit = powerOfTwo(-unit(local, b));
  PartWriter put(out);
  for (int g : groups_) {
    const MaterialGroup& grp = *local.groups()[size_t(g)];
    const double perKg = 1.0 / grp.density();
    std::unordered_map<uint64_t, int64_t> c; // integer sums: the same in any order
    const ParticleSet& P = grp.particles;
    for (size_t p = 0; p < P.size(); ++p) {
      const double fx = double(P.x[p][0]) * inv, fy = double(P.x[p][1]) * inv;
      const int32_t i = int32_t(std::floor(fx)), j = int32_t(std::floor(fy));
      const double tx = fx - i, ty = fy - j, v = double(P.mass[p]) * perKg;
      auto add = [&](int32_t a, int32_t b, double w) {
        if (w > 0) c[(uint64_t(uint32_t(a)) << 32) | uint32_t(b)] += toUnits(w * v, perUnit);
      };
      add(i, j, (1 - tx) * (1 - ty)), add(i + 1, j, tx * (1 - ty)), add(i, j + 1, (1 - tx) * ty), add(i + 1, j + 1, tx * ty);
    }
    std::vector<std::pair<uint64_t, int64_t>> sorted(c.begin(), c.end()); // the same bytes whatever the hash order
    std::sort(sorted.begin(), sorted.end());
    put.put(uint64_t(sorted.size()));
    for (const auto& [key, units] : sorted) put.put(key), put.put(units);
  }
}

std::vector<EntrainedMassColumns::Columns> EntrainedMassColumns::volumesFrom(const Simulation& sim, const PartBounds& b,
                                                                             const std::vector<std::string_view>& parts) const {
  std::vector<std::unordered_map<uint64_t, int64_t>> units(groups_.size());
  for (const auto& p : parts) {
    PartReader get(p);
    for (auto& u : units)
      for (uint64_t n = get.get<uint64_t>(); n > 0; --n) {
        const uint64_t key = get.get<uint64_t>();
        u[key] += get.get<int64_t>();
      }
    if (!get.done()) throw std::runtime_error("entrained mass: a part from another rank holds other materials");
  }
  const double size = powerOfTwo(unit(sim, b));
  std::vector<Columns> v(groups_.size());
  for (size_t k = 0; k < units.size(); ++k)
    for (const auto& [key, n] : units[k]) v[k][key] = double(n) * size;
  return v;
}

void EntrainedMassColumns::sampleParts(const Simulation& sim, double, const PartBounds& b,
                                       const std::vector<std::string_view>& parts, std::vector<double>& row) {
  const std::vector<Columns> now = volumesFrom(sim, b, parts);
  for (size_t k = 0; k < groups_.size(); ++k) {
    // Summed in key order: the same total whatever the hash map's iteration order.
    std::vector<std::pair<uint64_t, double>> lost;
    for (const auto& [key, v0] : start_[k]) {
      const auto it = now[k].find(key);
      const double v = it == now[k].end() ? 0.0 : it->second;
      if (v0 > v) lost.push_back({key, v0 - v});
    }
    std::sort(lost.begin(), lost.end());
    double sum = 0;
    for (const auto& l : lost) sum += l.second;
    row.push_back(sum * sim.groups()[size_t(groups_[k])]->density());
  }
}

} // namespace talus
