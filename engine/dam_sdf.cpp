#include "engine/dam_sdf.h"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

namespace talus {

namespace {

/// Signed distance from (d, z) to the convex polygon p (counter-clockwise).
double polygonDistance(double d, double z, const double (&p)[4][2]) {
  double best = std::numeric_limits<double>::infinity();
  bool inside = true;
  for (int i = 0; i < 4; ++i) {
    const double* a = p[i];
    const double* b = p[(i + 1) % 4];
    const double ex = b[0] - a[0], ez = b[1] - a[1], px = d - a[0], pz = z - a[1];
    const double len2 = ex * ex + ez * ez;
    const double t = len2 > 0 ? std::clamp((px * ex + pz * ez) / len2, 0.0, 1.0) : 0.0;
    best = std::min(best, std::hypot(px - t * ex, pz - t * ez));
    if (ex * pz - ez * px < 0) inside = false; // right of a counter-clockwise edge: outside
  }
  return inside ? -best : best;
}

} // namespace

DamSdf::DamSdf(std::vector<Vertex> line, double slopeDeg, double width, std::string description)
    : v_(std::move(line)), description_(std::move(description)) {
  if (v_.size() < 2) throw std::invalid_argument("a dam line needs two vertices at least");
  for (size_t i = 0; i < v_.size(); ++i) {
    if (!(v_[i].crest > v_[i].base)) throw std::invalid_argument("a dam's crest must lie above its base");
    if (i && std::hypot(v_[i].x - v_[i - 1].x, v_[i].y - v_[i - 1].y) <= 0)
      throw std::invalid_argument("a dam line has two vertices at one place");
  }
  if (!(slopeDeg > 0 && slopeDeg <= 90)) throw std::invalid_argument("a dam's slope must be in (0, 90] degrees");
  if (!(width >= 0)) throw std::invalid_argument("a dam's crest width must be >= 0");
  cot_ = slopeDeg >= 90 ? 0.0 : 1.0 / std::tan(slopeDeg * M_PI / 180);
  halfWidth_ = 0.5 * width;
}

double DamSdf::distance(const Vec3d& x) const {
  // The nearest segment in plan; along it the offset d (signed), the overshoot beyond the line's
  // ends, and the crest and base there.
  double bestPlan = std::numeric_limits<double>::infinity(), d = 0, beyond = 0, crest = 0, base = 0;
  for (size_t i = 0; i + 1 < v_.size(); ++i) {
    const Vertex &a = v_[i], &b = v_[i + 1];
    const double ex = b.x - a.x, ey = b.y - a.y, len = std::hypot(ex, ey);
    const double along = ((x.x() - a.x) * ex + (x.y() - a.y) * ey) / len;
    const double t = std::clamp(along / len, 0.0, 1.0);
    const double px = a.x + t * ex - x.x(), py = a.y + t * ey - x.y();
    const double plan = std::hypot(px, py);
    if (plan >= bestPlan) continue;
    bestPlan = plan;
    d = ((x.x() - a.x) * ey - (x.y() - a.y) * ex) / len;
    beyond = i == 0 && along < 0 ? -along : i + 2 == v_.size() && along > len ? along - len : 0.0;
    crest = a.crest + t * (b.crest - a.crest), base = a.base + t * (b.base - a.base);
  }
  const double foot = halfWidth_ + (crest - base) * cot_;
  const double p[4][2] = {{-foot, base}, {foot, base}, {halfWidth_, crest}, {-halfWidth_, crest}};
  const double section = polygonDistance(d, x.z(), p);
  if (beyond <= 0) return section;
  return section > 0 ? std::hypot(section, beyond) : beyond;
}

void DamSdf::bounds(Vec3d& lo, Vec3d& hi) const {
  lo = Vec3d::Constant(std::numeric_limits<double>::infinity());
  hi = -lo;
  for (const Vertex& v : v_) {
    const double r = halfWidth_ + (v.crest - v.base) * cot_;
    lo = lo.cwiseMin(Vec3d(v.x - r, v.y - r, v.base));
    hi = hi.cwiseMax(Vec3d(v.x + r, v.y + r, v.crest));
  }
}

} // namespace talus
