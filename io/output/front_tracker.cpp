#include "io/output/front_tracker.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <tbb/blocked_range.h>
#include <tbb/parallel_reduce.h>

namespace talus {

FrontTracker::FrontTracker(PathSpec spec, double defaultThreshold)
    : spec_(std::move(spec)), threshold_(spec_.threshold > 0 ? spec_.threshold : defaultThreshold) {}

void FrontTracker::onStart(const Simulation& sim) {
  const Vec3d o = sim.settings().origin;
  std::vector<Eigen::Vector2d> local;
  for (const auto& p : spec_.points) local.push_back(p - o.head<2>());
  path_ = Polyline(std::move(local));
  bin_ = sim.settings().dx;
  lanes_ = 1 + 2 * int(std::ceil(spec_.halfWidth / bin_ - 1e-9));
  previous_ = std::numeric_limits<double>::quiet_NaN();
}

std::vector<std::string> FrontTracker::header() const {
  return {"front_m_" + spec_.name, "front_speed_m_s_" + spec_.name};
}

int FrontTracker::binsAlong() const { return std::max(1, int(std::ceil(length() / bin_))); }

int FrontTracker::volumeUnit(const Simulation& sim, const PartBounds& b) {
  return unitExponent(volumeBound(sim, b), kCellBits);
}

void FrontTracker::part(const Simulation& local, const PartBounds& b, std::vector<char>& out) const {
  const int nbins = binsAlong();
  const int half = lanes_ / 2;
  const double reach = (half + 0.5) * bin_; // lateral extent of the corridor
  const double perUnit = powerOfTwo(-volumeUnit(local, b));
  Eigen::Vector2d lo = path_.points()[0], hi = lo;
  for (const auto& p : path_.points()) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  lo.array() -= reach, hi.array() += reach;
  const float minSpeed2 = float(spec_.minSpeed * spec_.minSpeed);
  using Bins = std::vector<int64_t>;
  Bins vol(size_t(nbins) * size_t(lanes_), 0);
  for (const MaterialGroup* g : local.groups()) {
    if (!spec_.materials.empty() &&
        std::find(spec_.materials.begin(), spec_.materials.end(), g->name()) == spec_.materials.end())
      continue;
    const ParticleSet& P = g->particles;
    const double invRho = 1.0 / g->density();
    // Chunks bin in parallel into their own arrays of fixed-point volumes: integer sums, the same
    // at any thread and rank count.
    auto binRange = [&](const tbb::blocked_range<size_t>& range, Bins acc) {
      if (acc.empty()) acc.assign(vol.size(), 0);
      for (size_t p = range.begin(); p != range.end(); ++p) {
        const Eigen::Vector2d x(P.x[p][0], P.x[p][1]);
        if (x.x() < lo.x() || x.y() < lo.y() || x.x() > hi.x() || x.y() > hi.y()) continue;
        if (minSpeed2 > 0 && P.v[p].squaredNorm() < minSpeed2) continue;
        // Nearest point of the path (beyond its ends nothing counts): along it and lateral (left > 0).
        double s, lateral;
        if (!(path_.nearestWithin(x, s, lateral) <= reach)) continue;
        const int lane = std::clamp(int(std::floor(lateral / bin_ + 0.5)) + half, 0, lanes_ - 1);
        const double fs = s / bin_ - 0.5;
        const int b0 = int(std::floor(fs));
        const double w1 = fs - b0;
        const double v = double(P.mass[p]) * invRho;
        const int64_t v0 = toUnits((1 - w1) * v, perUnit), v1 = toUnits(w1 * v, perUnit);
        int64_t* lb = acc.data() + size_t(lane) * nbins;
        // The outer half-bins at both ends fold into the end bins: no volume is lost.
        lb[std::clamp(b0, 0, nbins - 1)] += v0;
        lb[std::clamp(b0 + 1, 0, nbins - 1)] += v1;
      }
      return acc;
    };
    const Bins groupVol = tbb::parallel_reduce(
        tbb::blocked_range<size_t>(0, P.size(), 16384), Bins(), binRange, [](Bins a, const Bins& c) {
          if (a.empty()) return c;
          for (size_t i = 0; i < c.size(); ++i) a[i] += c[i];
          return a;
        });
    for (size_t i = 0; i < groupVol.size(); ++i) vol[i] += groupVol[i];
  }
  PartWriter put(out);
  for (int64_t v : vol) put.put(v);
}

double FrontTracker::frontOf(const Simulation& sim, const PartBounds& b, const std::vector<std::string_view>& parts) const {
  const double L = length();
  const int nbins = binsAlong();
  std::vector<int64_t> sum(size_t(nbins) * size_t(lanes_), 0);
  for (const auto& p : parts) {
    PartReader get(p);
    for (int64_t& v : sum) v += get.get<int64_t>();
  }
  const double invArea = powerOfTwo(volumeUnit(sim, b)) / (bin_ * bin_);
  double frontPos = std::numeric_limits<double>::quiet_NaN();
  for (int lane = 0; lane < lanes_; ++lane) {
    const int64_t* t = sum.data() + size_t(lane) * nbins;
    for (int k = nbins - 1; k >= 0; --k) {
      const double tb = double(t[k]) * invArea;
      if (tb < threshold_) continue;
      // Where the profile between this bin's centre and the next drops below the threshold.
      const double next = k + 1 < nbins ? double(t[k + 1]) * invArea : 0.0;
      const double pos = std::min(L, (k + 0.5) * bin_ + bin_ * (tb - threshold_) / (tb - next));
      if (!(pos <= frontPos)) frontPos = pos;
      break;
    }
  }
  return frontPos;
}

double FrontTracker::front(const Simulation& sim) const {
  std::vector<char> own;
  const PartBounds b = PartBounds::of(sim);
  part(sim, b, own);
  return frontOf(sim, b, {std::string_view(own.data(), own.size())});
}

void FrontTracker::sampleParts(const Simulation& sim, double elapsed, const PartBounds& b,
                               const std::vector<std::string_view>& parts, std::vector<double>& row) {
  const double f = frontOf(sim, b, parts);
  row.push_back(f);
  row.push_back(elapsed > 0 && std::isfinite(f) && std::isfinite(previous_) ? (f - previous_) / elapsed
                                                                             : std::numeric_limits<double>::quiet_NaN());
  previous_ = f;
}

} // namespace talus
