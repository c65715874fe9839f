#include "hazard/aimec.h"

#include "io/terrain/dem_raster.h"

#include <algorithm>
#include <cmath>
#include <memory>
#include <stdexcept>

namespace talus::aimec {

namespace {

bool inside(const RasterGrid& g, double x, double y) {
  return x >= g.originX && x <= g.originX + g.nx * g.cellSize && y <= g.originY && y >= g.originY - g.ny * g.cellSize;
}

} // namespace

Transform makeTransform(const Polyline& path, double width, double cellSize, const DemRaster* dem) {
  if (path.points().size() < 2 || !(path.length() > 0)) throw std::invalid_argument("the path needs two distinct points");
  if (!(width > 0) || !(cellSize > 0)) throw std::invalid_argument("domain width and cell size must be positive");
  Transform t;
  t.width = width, t.cellSize = cellSize;
  const double L = path.length();
  t.ns = size_t(std::ceil(L / cellSize - 1e-9)) + 1;
  std::vector<Eigen::Vector2d> c(t.ns);
  for (size_t i = 0; i < t.ns; ++i) {
    t.s.push_back(std::min(L, double(i) * cellSize));
    c[i] = path.at(t.s[i]);
  }
  size_t n = size_t(std::ceil(width / cellSize - 1e-9));
  if (n % 2 == 0) ++n; // odd, so that l = 0 (the path itself) is a lane, as AIMEC
  t.nl = n;
  const long half = long(n / 2);
  for (long k = -half; k <= half; ++k) t.l.push_back(double(k) * cellSize);
  t.x.resize(t.ns * t.nl), t.y.resize(t.ns * t.nl), t.area.resize(t.ns * t.nl);
  for (size_t i = 0; i < t.ns; ++i) {
    // Central differences along the resampled line: at a bend the cross-section bisects it.
    const Eigen::Vector2d d = (c[std::min(i + 1, t.ns - 1)] - c[i > 0 ? i - 1 : 0]).normalized();
    const Eigen::Vector2d nrm(-d.y(), d.x()); // left of the direction of travel
    for (size_t k = 0; k < t.nl; ++k) {
      const Eigen::Vector2d p = c[i] + t.l[k] * nrm;
      t.x[t.index(i, k)] = p.x(), t.y[t.index(i, k)] = p.y();
    }
  }
  std::unique_ptr<HeightField> ground;
  if (dem) ground = std::make_unique<HeightField>(*dem);
  for (size_t i = 0; i < t.ns; ++i) {
    const size_t a = i > 0 ? i - 1 : 0, b = std::min(i + 1, t.ns - 1);
    for (size_t k = 0; k < t.nl; ++k) {
      // The cell spans half-way to its neighbours along s (lanes fan out or close at bends).
      const double ds = std::hypot(t.x[t.index(b, k)] - t.x[t.index(a, k)], t.y[t.index(b, k)] - t.y[t.index(a, k)]) /
                        double(b - a == 2 ? 2 : 1) * (i == 0 || i + 1 == t.ns ? 0.5 : 1.0);
      double coef = 1;
      const double x = t.x[t.index(i, k)], y = t.y[t.index(i, k)];
      if (ground && inside(dem->grid, x, y)) {
        double gx, gy;
        ground->slopeGradient(x, y, gx, gy);
        if (std::isfinite(gx) && std::isfinite(gy)) coef = std::sqrt(1 + gx * gx + gy * gy);
      }
      t.area[t.index(i, k)] = ds * cellSize * coef;
    }
    t.zThalweg.push_back(ground && inside(dem->grid, c[i].x(), c[i].y()) ? ground->height(c[i].x(), c[i].y()) : kNaN);
  }
  return t;
}

std::vector<float> resample(const Transform& t, const DemRaster& r) {
  std::vector<float> out(t.x.size(), NAN);
  for (size_t p = 0; p < out.size(); ++p)
    if (inside(r.grid, t.x[p], t.y[p])) out[p] = float(sampleBilinear(r.grid, r.height, t.x[p], t.y[p]));
  return out;
}

PathStats analyse(const Transform& t, const std::vector<float>& f, double threshold) {
  PathStats st;
  st.threshold = threshold;
  for (size_t i = 0; i < t.ns; ++i) {
    double mx = kNaN, sum = 0, area = 0;
    for (size_t k = 0; k < t.nl; ++k) {
      const double v = f[t.index(i, k)];
      if (!std::isfinite(v)) continue;
      if (!(mx >= v)) mx = v;
      if (!(st.fieldMax >= v)) st.fieldMax = v;
      if (v > 0) sum += v * t.area[t.index(i, k)], area += t.area[t.index(i, k)];
    }
    st.crossMax.push_back(mx);
    st.crossMean.push_back(std::isfinite(mx) ? (area > 0 ? sum / area : 0.0) : kNaN);
    st.crossIntegral.push_back(std::isfinite(mx) ? sum / t.cellSize : kNaN); // a cross-section stands for cellSize of s
  }
  bool meanFound = false;
  size_t iMean = 0;
  for (size_t i = 0; i < t.ns; ++i) {
    if (st.crossMax[i] > threshold) {
      if (!st.found) st.iStart = i;
      st.found = true, st.iRunout = i;
    }
    if (st.crossMean[i] > threshold) meanFound = true, iMean = i;
  }
  if (meanFound) {
    st.sMeanRunout = t.s[iMean];
    st.xMeanRunout = t.x[t.index(iMean, t.nl / 2)], st.yMeanRunout = t.y[t.index(iMean, t.nl / 2)];
  }
  if (!st.found) return st;
  const size_t i0 = st.iStart, i1 = st.iRunout;
  size_t kMax = 0;
  for (size_t k = 0; k < t.nl; ++k) {
    const double v = f[t.index(i1, k)];
    if (std::isfinite(v) && !(f[t.index(i1, kMax)] >= v)) kMax = k;
  }
  st.sStart = t.s[i0], st.sRunout = t.s[i1], st.lRunout = t.l[kMax];
  st.xRunout = t.x[t.index(i1, kMax)], st.yRunout = t.y[t.index(i1, kMax)];
  st.deltaSXY = st.sRunout - st.sStart;
  st.zRelease = t.zThalweg[i0], st.zRunout = t.zThalweg[i1];
  st.deltaZ = st.zRelease - st.zRunout;
  if (st.deltaSXY > 0) st.runoutAngle = std::atan(st.deltaZ / st.deltaSXY) * 180 / M_PI;
  double integral = 0;
  st.mma = st.crossMax[i0];
  for (size_t i = i0; i <= i1; ++i) {
    st.mma = std::max(st.mma, st.crossMax[i]);
    if (i > i0) integral += 0.5 * (st.crossMax[i] + st.crossMax[i - 1]) * (t.s[i] - t.s[i - 1]);
  }
  st.ama = st.deltaSXY > 0 ? integral / st.deltaSXY : st.crossMax[i0];
  return st;
}

AreaComparison compareAreas(const Transform& t, const std::vector<float>& sim, const std::vector<float>& ref,
                            double threshold, size_t start) {
  AreaComparison c;
  c.threshold = threshold;
  c.classes.assign(t.x.size(), 255);
  for (size_t i = start; i < t.ns; ++i)
    for (size_t k = 0; k < t.nl; ++k) {
      const size_t p = t.index(i, k);
      // AIMEC counts missing data as not reached; cells neither raster covers are left out.
      if (!std::isfinite(sim[p]) && !std::isfinite(ref[p])) continue;
      const bool s = sim[p] > threshold, r = ref[p] > threshold; // NaN compares false
      const double a = t.area[p];
      if (s && r) c.tp += a, c.classes[p] = 2;
      else if (s) c.fp += a, c.classes[p] = 3;
      else if (r) c.fn += a, c.classes[p] = 1;
      else c.tn += a, c.classes[p] = 0;
    }
  c.referenceArea = c.tp + c.fn;
  if (c.referenceArea > 0) {
    c.alphaTP = c.tp / c.referenceArea, c.alphaFP = c.fp / c.referenceArea;
    c.alphaFN = c.fn / c.referenceArea, c.alphaTN = c.tn / c.referenceArea;
  }
  const PathStats ps = analyse(t, sim, threshold), pr = analyse(t, ref, threshold);
  c.sRunoutSim = ps.sRunout, c.sRunoutRef = pr.sRunout;
  c.runoutDifference = ps.sRunout - pr.sRunout;
  return c;
}

size_t runoutAreaStart(const Transform& t, double angle, const Eigen::Vector2d* split, double dsMin) {
  if (t.ns < 3 || std::none_of(t.zThalweg.begin(), t.zThalweg.end(), [](double z) { return std::isfinite(z); })) return 0;
  size_t first = 0;
  if (split) {
    double best = INFINITY;
    for (size_t i = 0; i < t.ns; ++i) {
      const size_t p = t.index(i, t.nl / 2);
      const double d = std::hypot(t.x[p] - split->x(), t.y[p] - split->y());
      if (d < best) best = d, first = i;
    }
  }
  const double tanA = std::tan(angle * M_PI / 180);
  auto below = [&](size_t i) { // slope of the thalweg (central differences) below the angle
    const size_t a = i > 0 ? i - 1 : 0, b = std::min(i + 1, t.ns - 1);
    const double drop = t.zThalweg[a] - t.zThalweg[b], run = t.s[b] - t.s[a];
    return std::isfinite(drop) && run > 0 && drop / run < tanA;
  };
  for (size_t i = first; i < t.ns; ++i) {
    if (!below(i)) continue;
    bool stays = true;
    for (size_t j = i + 1; j < t.ns && t.s[j] - t.s[i] <= dsMin && stays; ++j) stays = below(j);
    if (stays) return i;
  }
  return t.ns;
}

} // namespace talus::aimec
