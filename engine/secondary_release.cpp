#include "engine/secondary_release.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>
#include <stdexcept>

namespace talus {

SecondaryReleases::SecondaryReleases(std::vector<HeldBody> bodies, double dx)
    : bodies_(std::move(bodies)), dx_(dx), released_(bodies_.size(), std::numeric_limits<double>::quiet_NaN()),
      baseline_(bodies_.size()), columns_(bodies_.size()) {
  for (size_t b = 0; b < bodies_.size(); ++b) {
    if (bodies_[b].x.size() != bodies_[b].mass.size() || bodies_[b].x.empty())
      throw std::invalid_argument("secondary release '" + bodies_[b].name + "' holds no particle");
    // The node columns nearest to its particles: where the flow over it is measured.
    std::set<uint64_t> cols;
    for (const Vec3& x : bodies_[b].x)
      cols.insert(columnKey(int32_t(std::lround(double(x.x()) / dx)), int32_t(std::lround(double(x.y()) / dx))));
    columns_[b].assign(cols.begin(), cols.end());
  }
}

size_t SecondaryReleases::emit(const SparseGrid& grid, double time, double, const std::vector<MaterialGroup*>& groups) {
  bool anyHeld = false;
  for (double t : released_) anyHeld |= std::isnan(t);
  if (!anyHeld) return 0;
  // Mass per node column over the held bodies' columns, in block then node order.
  std::unordered_map<uint64_t, double> mass;
  for (size_t b = 0; b < bodies_.size(); ++b)
    if (std::isnan(released_[b]))
      for (uint64_t k : columns_[b]) mass.emplace(k, 0.0);
  for (size_t blk = 0; blk < grid.blockCount(); ++blk) {
    const BlockCoord& c = grid.topology.coord(uint32_t(blk));
    const Vec4* nodes = grid.block(uint32_t(blk));
    for (int n = 0; n < kBlockNodes; ++n) {
      if (!(nodes[n][0] > 0)) continue;
      const int32_t i = c.x * kBlockDim + (n >> (2 * kBlockLog2)), j = c.y * kBlockDim + ((n >> kBlockLog2) & (kBlockDim - 1));
      const auto it = mass.find(columnKey(i, j));
      if (it != mass.end()) it->second += double(nodes[n][0]);
    }
  }
  if (!started_) { // the first step: what the columns hold before any flow arrives
    for (size_t b = 0; b < bodies_.size(); ++b)
      for (uint64_t k : columns_[b]) baseline_[b][k] = mass[k];
    started_ = true;
  }
  size_t made = 0;
  const double area = dx_ * dx_;
  for (size_t b = 0; b < bodies_.size(); ++b) {
    if (!std::isnan(released_[b])) continue;
    HeldBody& h = bodies_[b];
    bool reached = false;
    for (uint64_t k : columns_[b]) reached |= (mass[k] - baseline_[b][k]) / area >= h.triggerMassPerArea;
    if (!reached) continue;
    ParticleSet& P = groups[size_t(h.group)]->particles;
    P.x.insert(P.x.end(), h.x.begin(), h.x.end());
    P.v.resize(P.x.size(), Vec3::Zero());
    P.C.resize(P.x.size(), Mat3::Zero());
    P.tau.resize(P.x.size(), Sym3{});
    P.mass.insert(P.mass.end(), h.mass.begin(), h.mass.end());
    groups[size_t(h.group)]->resizeState(P.size());
    released_[b] = time;
    made += h.x.size();
  }
  return made;
}

void SecondaryReleases::save(StateArchive& a, const std::string& prefix) const {
  a.putVector(prefix + "released", released_);
  a.putValue(prefix + "started", int32_t(started_));
  for (size_t b = 0; b < bodies_.size(); ++b) {
    std::vector<double> base;
    for (uint64_t k : columns_[b]) base.push_back(started_ ? baseline_[b].at(k) : 0.0);
    a.putVector(prefix + "baseline" + std::to_string(b), base);
  }
}

void SecondaryReleases::load(const StateArchive& a, const std::string& prefix) {
  std::vector<double> released;
  a.getVector(prefix + "released", released);
  if (released.size() != bodies_.size()) throw std::runtime_error("checkpoint holds other secondary releases than the scene");
  released_ = released;
  started_ = a.getValue<int32_t>(prefix + "started") != 0;
  for (size_t b = 0; b < bodies_.size(); ++b) {
    std::vector<double> base;
    a.getVector(prefix + "baseline" + std::to_string(b), base);
    if (base.size() != columns_[b].size()) throw std::runtime_error("checkpoint's secondary release does not fit the scene's");
    for (size_t c = 0; c < base.size(); ++c) baseline_[b][columns_[b][c]] = base[c];
  }
}

} // namespace talus
