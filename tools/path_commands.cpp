#include "tools/path_commands.h"

#include "hazard/aimec.h"
#include "io/output/map_quicklook.h"
#include "io/output/series_plots.h"
#include "tools/analysis.h"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace talus {

namespace {

std::string num(double v, const char* fmt = "%.1f") {
  if (!std::isfinite(v)) return "-";
  char b[64];
  std::snprintf(b, sizeof b, fmt, v);
  return b;
}

struct Setup {
  Polyline path;
  DemRaster dem;
  bool hasDem = false;
  aimec::Transform t;
  size_t start = 0; ///< first cross-section of the run-out area (0: all)
};

Setup setup(const AnalysisOptions& o, double rasterCell, const std::string& demFile) {
  if (o.path.empty()) throw std::invalid_argument("--aimec needs the thalweg: --path \"x,y x,y ...\" or a line file (path_aimec.shp)");
  Setup s;
  s.path = Polyline::parse(o.path);
  if (!demFile.empty()) s.dem = analysis::readRaster(demFile), s.hasDem = true;
  s.t = aimec::makeTransform(s.path, o.domainWidth, o.cellSL > 0 ? o.cellSL : rasterCell, s.hasDem ? &s.dem : nullptr);
  if (o.runoutAreaAngle > 0) {
    if (!s.hasDem) throw std::invalid_argument("--runout-area needs the DEM (--dem or --ground) for the thalweg's slope");
    Eigen::Vector2d split;
    if (!o.splitPoint.empty()) {
      char* end = nullptr;
      split.x() = std::strtod(o.splitPoint.c_str(), &end);
      if (!end || *end != ',') throw std::invalid_argument("--split-point '" + o.splitPoint + "': expected x,y");
      const char* y = end + 1;
      split.y() = std::strtod(y, &end);
      if (end == y || *end || !split.allFinite())
        throw std::invalid_argument("--split-point '" + o.splitPoint + "': expected x,y");
    }
    s.start = aimec::runoutAreaStart(s.t, o.runoutAreaAngle, o.splitPoint.empty() ? nullptr : &split);
    if (s.start >= s.t.ns) throw std::invalid_argument("the thalweg never flattens below --runout-area degrees");
  }
  std::printf("AIMEC (s, l) grid: %zu cross-sections over %.1f m of path, %zu lanes over %g m, cell %g m%s\n", s.t.ns,
              s.t.s.back(), s.t.nl, o.domainWidth, s.t.cellSize, s.hasDem ? ", real (slope) cell areas" : "");
  if (s.start > 0) std::printf("run-out area from s = %.1f m (thalweg below %g deg)\n", s.t.s[s.start], o.runoutAreaAngle);
  return s;
}

/// An (s, l) field as a picture: s to the right, l (left of the path) up.
void drawSL(const std::string& png, const aimec::Transform& t, const std::vector<float>& v, QuicklookStyle st) {
  RasterGrid g;
  g.nx = int(t.ns), g.ny = int(t.nl), g.cellSize = t.cellSize;
  g.originX = -0.5 * t.cellSize, g.originY = t.l.back() + 0.5 * t.cellSize;
  std::vector<float> img(g.size(), -9999.f);
  for (size_t r = 0; r < t.nl; ++r)
    for (size_t c = 0; c < t.ns; ++c) {
      const float x = v[t.index(c, t.nl - 1 - r)];
      if (std::isfinite(x)) img[r * t.ns + c] = x;
    }
  st.northUp = false;
  st.subtitle += (st.subtitle.empty() ? "" : "; ") + std::string("s along the path to the right, l left of it up");
  writeMapQuicklook(png, g, img, {}, st, -9999.f);
  std::printf("(s, l) map: %s\n", png.c_str());
}

/// The axis label of a raster: AvaFrame's result type from the file name, else its name.
std::string valueLabel(const std::string& file) {
  const std::string stem = std::filesystem::path(file).stem().string();
  auto ends = [&](const char* t) { return stem.size() > 4 && stem.compare(stem.size() - 4, 4, t) == 0; };
  if (ends("_ppr")) return "peak pressure (kPa)";
  if (ends("_pft")) return "peak flow thickness (m)";
  if (ends("_pfv")) return "peak flow velocity (m/s)";
  if (ends("_pfd")) return "peak flow depth, vertical (m)";
  return analysis::defaultLabel(file);
}

} // namespace

void addAimecOptions(CLI::App* mapStats, CLI::App* compare, AnalysisOptions& o) {
  for (CLI::App* c : {mapStats, compare}) {
    c->add_flag("--aimec", o.aimec, "AvaFrame AIMEC path analysis in (s, l) coordinates along --path");
    c->add_option("--domain-width", o.domainWidth, "AIMEC domain width across the path (m, default 600)")
        ->check(CLI::PositiveNumber);
    c->add_option("--cell-sl", o.cellSL, "(s, l) cell size (m; default: the (reference) raster's)")->check(CLI::PositiveNumber);
    c->add_option("--runout-area", o.runoutAreaAngle,
                  "Compare from where the thalweg flattens below this angle (deg), as AIMEC's defineRunoutArea");
    c->add_option("--split-point", o.splitPoint, "x,y: the run-out area starts after this point (splitPoint.shp)");
  }
  mapStats->add_option("--dem", o.dem, "DEM: elevations along the path (runout angle) and real cell areas");
  mapStats->add_option("--png", o.png, "(s, l) picture of the field (with --aimec)");
  mapStats->add_option("--plot", o.plot, "Peak values along s: cross-section maximum and mean (with --aimec)");
  mapStats->add_option("--out", o.csv, "CSV of s, cross-section maximum, mean, integral per metre and its sum (with --aimec)");
  mapStats->add_option("--scale", o.scale, "Multiplies the section integrals, e.g. a cover's density: an erosion depth's "
                                           "kg per metre of path (with --aimec)");
  mapStats->add_option("--integral-plot", o.integralPlot, "The section integral per metre along s (with --aimec)");
  mapStats->add_option("--integral-label", o.integralLabel, "Its axis label, e.g. \"entrained snow (kg/m)\"");
  mapStats->add_option("--title", o.title, "Title of the plot and the picture (with --aimec)");
}

int runAimecMapStats(const AnalysisOptions& o) {
  const DemRaster r = analysis::readRaster(o.rasters.at(0));
  const Setup s = setup(o, r.grid.cellSize, !o.dem.empty() ? o.dem : o.ground);
  const std::vector<float> f = aimec::resample(s.t, r);
  std::printf("%10s %9s %9s %8s %12s %12s %9s %8s %9s %9s %9s\n", "threshold", "s_start", "s_runout", "l_runout",
              "x_runout", "y_runout", "deltaSXY", "angle", "MMA", "AMA", "s_mean");
  const std::vector<double> ts = o.thresholds.empty() ? std::vector<double>{0} : o.thresholds;
  for (double th : ts) {
    const aimec::PathStats p = aimec::analyse(s.t, f, th);
    std::printf("%10g %9s %9s %8s %12s %12s %9s %8s %9s %9s %9s%s\n", th, num(p.sStart).c_str(), num(p.sRunout).c_str(),
                num(p.lRunout).c_str(), num(p.xRunout, "%.2f").c_str(), num(p.yRunout, "%.2f").c_str(),
                num(p.deltaSXY).c_str(), num(p.runoutAngle, "%.2f").c_str(), num(p.mma, "%.4g").c_str(),
                num(p.ama, "%.4g").c_str(), num(p.sMeanRunout).c_str(), p.found ? "" : "  (never above the threshold)");
  }
  const aimec::PathStats p = aimec::analyse(s.t, f, ts.front());
  // The section integrals (times --scale) per metre of s and summed from the path's start.
  std::vector<double> perMetre, running;
  double sum = 0;
  for (size_t i = 0; i < s.t.ns; ++i) {
    const double v = o.scale * p.crossIntegral[i];
    perMetre.push_back(v);
    if (std::isfinite(v)) sum += v * s.t.cellSize;
    running.push_back(sum);
  }
  if (o.scale != 1 || !o.integralPlot.empty()) std::printf("integral over the (s, l) grid (x %g): %.6g\n", o.scale, sum);
  if (!o.csv.empty()) {
    std::ofstream out(o.csv);
    out << "s_m,z_thalweg_m,cross_max,cross_mean,cross_integral_per_m,cumulative\n";
    for (size_t i = 0; i < s.t.ns; ++i)
      out << num(s.t.s[i], "%.3f") << "," << num(s.t.zThalweg[i], "%.3f") << "," << num(p.crossMax[i], "%.6g") << ","
          << num(p.crossMean[i], "%.6g") << "," << num(perMetre[i], "%.6g") << "," << num(running[i], "%.6g") << "\n";
    std::printf("table: %s\n", o.csv.c_str());
  }
  if (!o.integralPlot.empty()) {
    writeLineChart(o.integralPlot,
                   o.title.empty() ? "Section integral per metre of path (in all " + num(sum, "%.4g") + ")" : o.title,
                   "s along the path (m)",
                   o.integralLabel.empty() ? valueLabel(o.rasters[0]) + " x m2 per m (x " + num(o.scale, "%g") + ")"
                                           : o.integralLabel,
                   s.t.s,
                   {{"per metre of path", perMetre, false}});
    std::printf("plot: %s\n", o.integralPlot.c_str());
  }
  if (!o.plot.empty()) {
    std::vector<double> lim(s.t.ns, ts.front());
    writeLineChart(o.plot,
                   o.title.empty() ? "Peak values along the path (run-out " + num(p.sRunout) + " m above " + num(ts.front(), "%g") + ")"
                                   : o.title,
                   "s along the path (m)", valueLabel(o.rasters[0]), s.t.s,
                   {{"cross-section maximum", p.crossMax, false}, {"cross-section mean", p.crossMean, false},
                    {"threshold", lim, false}});
    std::printf("plot: %s\n", o.plot.c_str());
  }
  if (!o.png.empty()) {
    QuicklookStyle st;
    st.title = o.title.empty() ? analysis::defaultLabel(o.rasters[0]) + " in AIMEC's (s, l) coordinates" : o.title;
    drawSL(o.png, s.t, f, st);
  }
  return 0;
}

int runAimecCompare(const AnalysisOptions& o) {
  const DemRaster sim = analysis::readRaster(o.simulation), ref = analysis::readRaster(o.reference);
  const Setup s = setup(o, ref.grid.cellSize, o.dem);
  const std::vector<float> fs = aimec::resample(s.t, sim), fr = aimec::resample(s.t, ref);
  std::printf("areas in m2 (real area with --dem); alpha = area / reference area (TP + FN), as AIMEC\n");
  std::printf("%9s %11s %11s %11s %12s %7s %7s %7s %10s %10s %9s\n", "threshold", "TP", "FP", "FN", "TN", "aTP", "aFP",
              "aFN", "runout_sim", "runout_ref", "d_runout");
  const std::vector<double> ts = o.thresholds.empty() ? std::vector<double>{0} : o.thresholds;
  for (double th : ts) {
    const aimec::AreaComparison c = aimec::compareAreas(s.t, fs, fr, th, s.start);
    std::printf("%9g %11.0f %11.0f %11.0f %12.0f %7s %7s %7s %10s %10s %9s\n", th, c.tp, c.fp, c.fn, c.tn,
                num(c.alphaTP, "%.3f").c_str(), num(c.alphaFP, "%.3f").c_str(), num(c.alphaFN, "%.3f").c_str(),
                num(c.sRunoutSim).c_str(), num(c.sRunoutRef).c_str(), num(c.runoutDifference, "%+.1f").c_str());
  }
  if (!o.png.empty()) {
    const aimec::AreaComparison c = aimec::compareAreas(s.t, fs, fr, ts.front(), s.start);
    std::vector<float> cls;
    for (uint8_t k : c.classes) cls.push_back(k == 255 ? NAN : float(k)); // 255: outside the compared part
    QuicklookStyle st;
    st.title = o.title.empty() ? "Simulation against reference along the path" : o.title;
    st.subtitle = "above " + num(ts.front(), "%g") + ", run-out difference " + num(c.runoutDifference, "%+.0f") + " m";
    st.classes = {{"ref. only (FN)", {0.17, 0.45, 0.80}}, {"both (TP)", {0.45, 0.25, 0.55}},
                  {"sim. only (FP)", {0.85, 0.25, 0.15}}};
    drawSL(o.png, s.t, cls, st);
  }
  return 0;
}

} // namespace talus
