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

double FrontTracker::front(const Simulation& sim) const {
  const double L = length();
  const int nbins = std::max(1, int(std::ceil(L / bin_)));
  const int half = lanes_ / 2;
  const double reach = (half + 0.5) * bin_; // lateral extent of the corridor
  std::vector<double> vol(size_t(nbins) * size_t(lanes_), 0.0);
  Eigen::Vector2d lo = path_.points()[0], hi = lo;
  for (const auto& p : path_.points()) lo = lo.cwiseMin(p), hi = hi.cwiseMax(p);
  lo.array() -= reach, hi.array() += reach;
  const float minSpeed2 = float(spec_.minSpeed * spec_.minSpeed);
  for (const MaterialGroup* g : sim.groups()) {
    if (!spec_.materials.empty() &&
        std::find(spec_.materials.begin(), spec_.materials.end(), g->name()) == spec_.materials.end())
      continue;
    const ParticleSet& P = g->particles;
    const double invRho = 1.0 / g->density();
    // Chunks bin in parallel into their own arrays, summed in a fixed tree: the same front at
    // any thread count.
    auto binRange = [&](const tbb::blocked_range<size_t>& range, std::vector<double> acc) {
      if (acc.empty()) acc.assign(vol.size(), 0.0);
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
        double* lb = acc.data() + size_t(lane) * nbins;
        if (b0 >= 0 && b0 < nbins) lb[b0] += (1 - w1) * v;
        if (b0 + 1 >= 0 && b0 + 1 < nbins) lb[b0 + 1] += w1 * v;
        // The outer half-bins at both ends fold into the end bins: no volume is lost.
        if (b0 < 0) lb[0] += (1 - w1) * v;
        if (b0 + 1 >= nbins) lb[nbins - 1] += w1 * v;
      }
      return acc;
    };
    const std::vector<double> groupVol = tbb::parallel_deterministic_reduce(
        tbb::blocked_range<size_t>(0, P.size(), 16384), std::vector<double>(), binRange,
        [](std::vector<double> a, const std::vector<double>& b) {
          if (a.empty()) return b;
          for (size_t i = 0; i < b.size(); ++i) a[i] += b[i];
          return a;
        });
    for (size_t i = 0; i < groupVol.size(); ++i) vol[i] += groupVol[i];
  }
  const double invArea = 1.0 / (bin_ * bin_);
  double frontPos = std::numeric_limits<double>::quiet_NaN();
  for (int lane = 0; lane < lanes_; ++lane) {
    const double* t = vol.data() + size_t(lane) * nbins;
    for (int b = nbins - 1; b >= 0; --b) {
      const double tb = t[b] * invArea;
      if (tb < threshold_) continue;
      // Where the profile between this bin's centre and the next drops below the threshold.
      const double next = b + 1 < nbins ? t[b + 1] * invArea : 0.0;
      const double pos = std::min(L, (b + 0.5) * bin_ + bin_ * (tb - threshold_) / (tb - next));
      if (!(pos <= frontPos)) frontPos = pos;
      break;
    }
  }
  return frontPos;
}

void FrontTracker::sample(const Simulation& sim, double elapsed, std::vector<double>& row) {
  const double f = front(sim);
  row.push_back(f);
  row.push_back(elapsed > 0 && std::isfinite(f) && std::isfinite(previous_) ? (f - previous_) / elapsed
                                                                             : std::numeric_limits<double>::quiet_NaN());
  previous_ = f;
}

} // namespace talus
