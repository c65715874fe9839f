#include "io/output/water_gauges.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

namespace talus {

namespace {

long long bucketKey(long long ix, long long iy) { return ix * 2654435761LL + iy; }

/// Per gauge: the tent-weighted water volume (m, a depth) and the lowest particle (local z).
struct Reading {
  std::vector<double> depth, zLow;
  explicit Reading(size_t n = 0) : depth(n, 0.0), zLow(n, std::numeric_limits<double>::infinity()) {}
  void add(const Reading& o) {
    for (size_t k = 0; k < depth.size(); ++k) depth[k] += o.depth[k], zLow[k] = std::min(zLow[k], o.zLow[k]);
  }
};

} // namespace

std::vector<const MaterialGroup*> waterGroups(const Simulation& sim, const std::vector<std::string>& names) {
  std::vector<const MaterialGroup*> water;
  for (const auto* g : sim.groups()) {
    const bool listed = std::find(names.begin(), names.end(), g->name()) != names.end();
    if (names.empty() ? std::string(g->modelName()) == "water" : listed) water.push_back(g);
  }
  return water;
}

WaterGauges::WaterGauges(std::vector<GaugeSpec> gauges, std::vector<std::string> waterMaterials, double particleSpacing)
    : gauges_(std::move(gauges)), waterMaterials_(std::move(waterMaterials)), spacing_(particleSpacing) {}

void WaterGauges::onStart(const Simulation& sim) {
  water_ = waterGroups(sim, waterMaterials_);
  if (water_.empty())
    throw std::runtime_error("gauge '" + gauges_.front().name +
                             "': the scene has no water (a material of model \"water\", or one listed in "
                             "[output] water_materials)");
  radius_.clear();
  double largest = 0;
  for (const auto& g : gauges_) {
    radius_.push_back(g.radius > 0 ? g.radius : sim.settings().dx);
    largest = std::max(largest, radius_.back());
  }
  // Hash cells at least as wide as a footprint: a footprint overlaps at most 2 x 2 of them.
  bucket_ = 2 * largest;
  buckets_.clear();
  const Vec3d o = sim.settings().origin;
  for (size_t k = 0; k < gauges_.size(); ++k) {
    const double x = gauges_[k].point.x() - o.x(), y = gauges_[k].point.y() - o.y(), r = radius_[k];
    for (long long ix = std::llround(std::floor((x - r) / bucket_)); ix <= std::llround(std::floor((x + r) / bucket_)); ++ix)
      for (long long iy = std::llround(std::floor((y - r) / bucket_)); iy <= std::llround(std::floor((y + r) / bucket_)); ++iy)
        buckets_.emplace_back(bucketKey(ix, iy), int(k));
  }
  std::sort(buckets_.begin(), buckets_.end());
}

std::vector<std::string> WaterGauges::header() const {
  std::vector<std::string> h;
  for (const auto& g : gauges_) h.push_back("water_surface_m_" + g.name);
  return h;
}

std::vector<double> WaterGauges::surfaces(const Simulation& sim) const {
  const Vec3d o = sim.settings().origin;
  const size_t n = gauges_.size();
  Reading total(n);
  for (const MaterialGroup* g : water_) {
    const ParticleSet& P = g->particles;
    const double inverseDensity = 1 / g->density();
    // Fixed chunks combined in a fixed tree: the same readings at any thread count.
    const Reading part = tbb::parallel_deterministic_reduce(
        tbb::blocked_range<size_t>(0, P.size(), 8192), Reading(n),
        [&](const tbb::blocked_range<size_t>& range, Reading acc) {
          for (size_t p = range.begin(); p != range.end(); ++p) {
            const double x = double(P.x[p].x()), y = double(P.x[p].y());
            const long long key = bucketKey(std::llround(std::floor(x / bucket_)), std::llround(std::floor(y / bucket_)));
            auto it = std::lower_bound(buckets_.begin(), buckets_.end(), std::make_pair(key, -1));
            for (; it != buckets_.end() && it->first == key; ++it) {
              const size_t k = size_t(it->second);
              const double r = radius_[k];
              const double wx = 1 - std::abs(x - (gauges_[k].point.x() - o.x())) / r;
              const double wy = 1 - std::abs(y - (gauges_[k].point.y() - o.y())) / r;
              if (wx <= 0 || wy <= 0) continue;
              acc.depth[k] += wx * wy / (r * r) * double(P.mass[p]) * inverseDensity;
              acc.zLow[k] = std::min(acc.zLow[k], double(P.x[p].z()));
            }
          }
          return acc;
        },
        [](Reading a, const Reading& b) {
          a.add(b);
          return a;
        });
    total.add(part);
  }
  std::vector<double> z(n, std::numeric_limits<double>::quiet_NaN());
  for (size_t k = 0; k < n; ++k)
    if (std::isfinite(total.zLow[k])) z[k] = total.zLow[k] - 0.5 * spacing_ + total.depth[k] + o.z();
  return z;
}

void WaterGauges::sample(const Simulation& sim, double, std::vector<double>& row) {
  const std::vector<double> z = surfaces(sim);
  row.insert(row.end(), z.begin(), z.end());
}

} // namespace talus
