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

/// Per gauge: the tent-weighted water volume (a depth, in the gauge's fixed-point unit) and the
/// lowest particle (local z): an integer sum and a minimum, exact in any order.
struct Reading {
  std::vector<__int128> depth;
  std::vector<double> zLow;
  explicit Reading(size_t n = 0) : depth(n, 0), zLow(n, std::numeric_limits<double>::infinity()) {}
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

std::vector<size_t> waterGroupIndices(const Simulation& sim, const std::vector<std::string>& names) {
  std::vector<size_t> water;
  for (const MaterialGroup* w : waterGroups(sim, names))
    for (size_t i = 0; i < sim.groups().size(); ++i)
      if (sim.groups()[i] == w) water.push_back(i);
  return water;
}

WaterGauges::WaterGauges(std::vector<GaugeSpec> gauges, std::vector<std::string> waterMaterials, double particleSpacing)
    : gauges_(std::move(gauges)), waterMaterials_(std::move(waterMaterials)), spacing_(particleSpacing) {}

void WaterGauges::onStart(const Simulation& sim) {
  water_ = waterGroupIndices(sim, waterMaterials_);
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

int WaterGauges::unit(const Simulation& sim, const PartBounds& b, size_t k) const {
  return unitExponent(volumeBound(sim, b) / (radius_[k] * radius_[k]), kTotalBits); // the largest weight is 1/r^2
}

void WaterGauges::part(const Simulation& local, const PartBounds& b, std::vector<char>& out) const {
  const Vec3d o = local.settings().origin;
  const size_t n = gauges_.size();
  std::vector<double> perUnit(n);
  for (size_t k = 0; k < n; ++k) perUnit[k] = powerOfTwo(-unit(local, b, k));
  Reading total(n);
  for (size_t g : water_) {
    const ParticleSet& P = local.groups()[g]->particles;
    const double inverseDensity = 1 / local.groups()[g]->density();
    total.add(tbb::parallel_reduce(
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
              acc.depth[k] += toUnits(wx * wy / (r * r) * double(P.mass[p]) * inverseDensity, perUnit[k]);
              acc.zLow[k] = std::min(acc.zLow[k], double(P.x[p].z()));
            }
          }
          return acc;
        },
        [](Reading a, const Reading& c) {
          a.add(c);
          return a;
        }));
  }
  PartWriter put(out);
  for (size_t k = 0; k < n; ++k) put.put(total.depth[k]), put.put(total.zLow[k]);
}

std::vector<double> WaterGauges::surfacesFrom(const Simulation& sim, const PartBounds& b,
                                              const std::vector<std::string_view>& parts) const {
  const size_t n = gauges_.size();
  Reading total(n);
  for (const auto& p : parts) {
    PartReader get(p);
    for (size_t k = 0; k < n; ++k) total.depth[k] += get.get<__int128>(), total.zLow[k] = std::min(total.zLow[k], get.get<double>());
  }
  const double oz = sim.settings().origin.z();
  std::vector<double> z(n, std::numeric_limits<double>::quiet_NaN());
  for (size_t k = 0; k < n; ++k)
    if (std::isfinite(total.zLow[k]))
      z[k] = total.zLow[k] - 0.5 * spacing_ + double(total.depth[k]) * powerOfTwo(unit(sim, b, k)) + oz;
  return z;
}

std::vector<double> WaterGauges::surfaces(const Simulation& sim) const {
  std::vector<char> own;
  const PartBounds b = PartBounds::of(sim);
  part(sim, b, own);
  return surfacesFrom(sim, b, {std::string_view(own.data(), own.size())});
}

std::vector<double> WaterGauges::depths(const Simulation& sim) const {
  std::vector<char> own;
  const PartBounds b = PartBounds::of(sim);
  part(sim, b, own);
  PartReader get(std::string_view(own.data(), own.size()));
  std::vector<double> d(gauges_.size());
  for (size_t k = 0; k < d.size(); ++k) {
    d[k] = double(get.get<__int128>()) * powerOfTwo(unit(sim, b, k));
    get.get<double>(); // the lowest particle: not needed for the column
  }
  return d;
}

void WaterGauges::sampleParts(const Simulation& sim, double, const PartBounds& b,
                              const std::vector<std::string_view>& parts, std::vector<double>& row) {
  const std::vector<double> z = surfacesFrom(sim, b, parts);
  row.insert(row.end(), z.begin(), z.end());
}

} // namespace talus
