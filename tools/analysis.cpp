#include "tools/analysis.h"

#include "io/terrain/dem_raster.h"

#include <algorithm>
#include <cmath>
#include <cpl_conv.h>
#include <cpl_error.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <gdal_priv.h>
#include <memory>
#include <ogrsf_frmts.h>
#include <sstream>
#include <stdexcept>

namespace talus::analysis {

std::string defaultLabel(const std::string& path) {
  const std::filesystem::path p(path);
  const std::string parent = p.parent_path().filename().string();
  if (parent.empty() || parent == "maps" || parent == ".") return p.stem().string();
  return parent + " " + p.stem().string();
}

DemRaster readRaster(const std::string& path) {
  DemReadOptions o;
  o.keepNodata = true;
  return readDem(path, o);
}

double sample(const DemRaster& r, double x, double y) {
  const RasterGrid& g = r.grid;
  const double cs = g.cellSize;
  if (x < g.originX || x > g.originX + g.nx * cs || y > g.originY || y < g.originY - g.ny * cs) return kNaN;
  const double fx = std::clamp((x - g.originX) / cs - 0.5, 0.0, double(g.nx - 1));
  const double fy = std::clamp((g.originY - y) / cs - 0.5, 0.0, double(g.ny - 1));
  const int c0 = std::min(int(fx), std::max(0, g.nx - 2)), r0 = std::min(int(fy), std::max(0, g.ny - 2));
  const double tx = g.nx > 1 ? fx - c0 : 0, ty = g.ny > 1 ? fy - r0 : 0;
  double sum = 0;
  for (int k = 0; k < 4; ++k) {
    const int dc = k & 1, dr = k >> 1;
    const double w = (dc ? tx : 1 - tx) * (dr ? ty : 1 - ty);
    if (w <= 0) continue;
    const double v = r.height[g.index(std::min(c0 + dc, g.nx - 1), std::min(r0 + dr, g.ny - 1))];
    if (!std::isfinite(v)) return kNaN;
    sum += w * v;
  }
  return sum;
}

DemRaster resample(const DemRaster& src, const RasterGrid& onto) {
  DemRaster out;
  out.grid = onto;
  out.sourcePath = src.sourcePath;
  out.height.resize(onto.size());
  for (int r = 0; r < onto.ny; ++r)
    for (int c = 0; c < onto.nx; ++c)
      out.height[onto.index(c, r)] = float(sample(src, onto.cellCentreX(c), onto.cellCentreY(r)));
  return out;
}

Profile profile(const Polyline& line, const std::vector<const DemRaster*>& rasters, double step) {
  if (!(step > 0)) throw std::invalid_argument("profile step must be positive");
  Profile p;
  p.values.resize(rasters.size());
  const double L = line.length();
  const size_t n = size_t(std::ceil(L / step - 1e-9)) + 1;
  for (size_t i = 0; i < n; ++i) {
    const double s = std::min(L, double(i) * step);
    const Eigen::Vector2d q = line.at(s);
    p.s.push_back(s), p.x.push_back(q.x()), p.y.push_back(q.y());
    for (size_t k = 0; k < rasters.size(); ++k) p.values[k].push_back(sample(*rasters[k], q.x(), q.y()));
  }
  return p;
}

MapStats mapStats(const DemRaster& r, double threshold, const DemRaster* ground, const Polyline* path, double halfWidth) {
  MapStats m;
  m.threshold = threshold;
  const RasterGrid& g = r.grid;
  const double a = g.cellSize * g.cellSize;
  double sum = 0;
  for (int row = 0; row < g.ny; ++row)
    for (int c = 0; c < g.nx; ++c) {
      const double v = r.height[g.index(c, row)];
      if (!std::isfinite(v)) continue;
      if (!(m.max >= v)) m.max = v;
      if (!(v >= threshold && v > 0)) continue;
      ++m.cells;
      sum += v;
      const double x = g.cellCentreX(c), y = g.cellCentreY(row);
      if (ground) {
        const double z = sample(*ground, x, y);
        if (std::isfinite(z)) {
          if (!(m.groundMin <= z)) m.groundMin = z;
          if (!(m.groundMax >= z)) m.groundMax = z;
        }
      }
      if (path) {
        double off = 0;
        bool beyond = false;
        const double s = path->project(Eigen::Vector2d(x, y), &off, &beyond);
        if (std::abs(off) <= halfWidth && !(m.runout >= s)) {
          m.runout = s, m.runoutX = x, m.runoutY = y;
        }
        if (std::abs(off) <= halfWidth && beyond && s >= path->length()) m.runoutBeyondEnd = true;
      }
    }
  m.area = double(m.cells) * a;
  m.volume = sum * a;
  if (m.cells) m.mean = sum / double(m.cells);
  return m;
}

Comparison compare(const DemRaster& sim, const DemRaster& ref, double threshold, const Polyline* path, double halfWidth) {
  if (sim.grid.nx != ref.grid.nx || sim.grid.ny != ref.grid.ny)
    throw std::invalid_argument("compare: resample the simulation onto the reference grid first");
  Comparison c;
  c.threshold = threshold;
  // Only cells where both rasters have data take part in every statistic.
  DemRaster s = sim, r = ref;
  for (size_t i = 0; i < r.height.size(); ++i)
    if (!std::isfinite(s.height[i]) || !std::isfinite(r.height[i])) s.height[i] = r.height[i] = NAN;
  c.sim = mapStats(s, threshold, nullptr, path, halfWidth);
  c.ref = mapStats(r, threshold, nullptr, path, halfWidth);
  const double a = ref.grid.cellSize * ref.grid.cellSize;
  double sumD = 0, sumD2 = 0;
  size_t n = 0;
  for (size_t i = 0; i < r.height.size(); ++i) {
    const double vs = s.height[i], vr = r.height[i];
    if (!std::isfinite(vs)) continue;
    const bool inS = vs >= threshold && vs > 0, inR = vr >= threshold && vr > 0;
    if (inS && inR) c.areaBoth += a;
    else if (inS) c.areaSimOnly += a;
    else if (inR) c.areaRefOnly += a;
    if (inS || inR) sumD += vs - vr, sumD2 += (vs - vr) * (vs - vr), ++n;
  }
  const double uni = c.areaBoth + c.areaSimOnly + c.areaRefOnly;
  if (uni > 0) c.overlap = c.areaBoth / uni;
  if (n) c.bias = sumD / double(n), c.rmse = std::sqrt(sumD2 / double(n));
  return c;
}

std::vector<float> overlapClasses(const DemRaster& sim, const DemRaster& ref, double threshold) {
  std::vector<float> out(ref.height.size(), NAN);
  for (size_t i = 0; i < out.size(); ++i) {
    const double vs = sim.height[i], vr = ref.height[i];
    if (!std::isfinite(vs) || !std::isfinite(vr)) continue;
    const bool inS = vs >= threshold && vs > 0, inR = vr >= threshold && vr > 0;
    out[i] = inS && inR ? 2.f : inS ? 3.f : inR ? 1.f : 0.f;
  }
  return out;
}

SeriesTable readSeries(const std::string& path) {
  std::ifstream in(path);
  if (!in) throw std::runtime_error(path + ": cannot read");
  SeriesTable t;
  std::string line;
  if (!std::getline(in, line)) throw std::runtime_error(path + ": empty");
  {
    std::istringstream h(line);
    std::string name;
    while (std::getline(h, name, ',')) t.header.push_back(name);
  }
  size_t lineNo = 1;
  while (std::getline(in, line)) {
    ++lineNo;
    if (line.empty()) continue;
    std::vector<double> row;
    std::istringstream r(line);
    std::string v;
    while (std::getline(r, v, ',')) row.push_back(std::strtod(v.c_str(), nullptr));
    if (row.size() != t.header.size())
      throw std::runtime_error(path + ":" + std::to_string(lineNo) + ": " + std::to_string(row.size()) + " values, " +
                               std::to_string(t.header.size()) + " columns");
    t.rows.push_back(std::move(row));
  }
  return t;
}

double timeBelowFraction(const SeriesTable& t, const std::string& column, double fraction) {
  const int c = t.column(column);
  if (c < 0 || t.rows.empty()) return kNaN;
  double peak = 0;
  size_t ip = 0;
  for (size_t i = 0; i < t.rows.size(); ++i)
    if (t.rows[i][size_t(c)] > peak) peak = t.rows[i][size_t(c)], ip = i;
  if (!(peak > 0)) return kNaN;
  const double limit = fraction * peak;
  size_t last = ip; // last row at or above the limit
  for (size_t i = ip; i < t.rows.size(); ++i)
    if (!(t.rows[i][size_t(c)] < limit)) last = i;
  if (last + 1 >= t.rows.size()) return kNaN;
  return t.rows[last + 1][0];
}

FrontSpeed frontSpeedAgainstDistance(const SeriesTable& t, const std::string& path, double step, double h) {
  FrontSpeed f;
  const int c = t.column("front_m_" + path);
  if (c < 0 || t.rows.empty() || !(step > 0) || !(h > 0)) return f;
  double reach = -std::numeric_limits<double>::infinity(), start = kNaN;
  for (const auto& r : t.rows)
    if (std::isfinite(r[size_t(c)])) {
      if (!std::isfinite(start)) start = r[size_t(c)];
      reach = std::max(reach, r[size_t(c)]);
    }
  if (!std::isfinite(start)) return f;
  // Arrival time at distance s: the first crossing of s by the front, interpolated linearly
  // between rows; the front before the first row with one is taken as absent.
  auto arrival = [&](double s) {
    double prevT = kNaN, prevF = kNaN;
    for (const auto& r : t.rows) {
      const double ft = r[size_t(c)], tt = r[0];
      if (std::isfinite(ft) && ft >= s) {
        if (std::isfinite(prevF) && prevF < s && ft > prevF) return prevT + (s - prevF) / (ft - prevF) * (tt - prevT);
        return tt;
      }
      if (std::isfinite(ft)) prevT = tt, prevF = ft;
    }
    return kNaN;
  };
  for (double s = 0; s <= reach + 1e-9; s += step) {
    f.s.push_back(s);
    f.arrival.push_back(s <= start ? kNaN : arrival(s));
  }
  for (size_t i = 0; i < f.s.size(); ++i) {
    const double s = f.s[i];
    double v = kNaN;
    if (s - h > start && s + h <= reach) {
      const double t0 = arrival(s - h), t1 = arrival(s + h);
      if (std::isfinite(t0) && std::isfinite(t1) && t1 > t0) v = 2 * h / (t1 - t0);
    }
    f.speed.push_back(v);
  }
  return f;
}

} // namespace talus::analysis
