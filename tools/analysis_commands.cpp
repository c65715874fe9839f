#include "tools/analysis_commands.h"

#include "io/terrain/dem_raster.h"
#include "io/output/map_quicklook.h"
#include "io/output/series_plots.h"
#include "tools/analysis.h"
#include "tools/path_commands.h"

#include <CLI/CLI.hpp>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <stdexcept>

namespace talus {

namespace fs = std::filesystem;
using namespace analysis;

namespace {

std::string num(double v, const char* fmt = "%.6g") {
  if (!std::isfinite(v)) return "-";
  char b[64];
  std::snprintf(b, sizeof b, fmt, v);
  return b;
}

void writeCsv(const std::string& path, const std::vector<std::string>& header,
              const std::vector<std::vector<double>>& columns) {
  std::ofstream f(path);
  if (!f) throw std::runtime_error(path + ": cannot write");
  for (size_t i = 0; i < header.size(); ++i) f << (i ? "," : "") << header[i];
  f << '\n';
  const size_t n = columns.empty() ? 0 : columns[0].size();
  for (size_t k = 0; k < n; ++k) {
    for (size_t i = 0; i < columns.size(); ++i) f << (i ? "," : "") << num(columns[i][k], "%.10g");
    f << '\n';
  }
  if (!f) throw std::runtime_error(path + ": cannot write");
}

int runProfile(const AnalysisOptions& o) {
  if (o.line.empty()) throw std::invalid_argument("profile: give the line with --line \"x,y x,y ...\" or a file");
  const Polyline line = Polyline::parse(o.line);
  std::vector<DemRaster> rasters;
  for (const auto& r : o.rasters) rasters.push_back(readRaster(r));
  std::vector<std::string> labels;
  for (size_t i = 0; i < o.rasters.size(); ++i)
    labels.push_back(i < o.labels.size() ? o.labels[i] : defaultLabel(o.rasters[i]));
  DemRaster ground;
  if (!o.ground.empty()) ground = readRaster(o.ground);
  std::vector<const DemRaster*> all;
  if (!o.ground.empty()) all.push_back(&ground);
  for (const auto& r : rasters) all.push_back(&r);
  const double step = o.step > 0 ? o.step : all.front()->grid.cellSize;
  const Profile p = profile(line, all, step);

  std::vector<std::string> header{"distance_m", "x", "y"};
  std::vector<std::vector<double>> cols{p.s, p.x, p.y};
  if (!o.ground.empty()) header.push_back("ground_m");
  for (const auto& l : labels) header.push_back(l);
  for (const auto& v : p.values) cols.push_back(v);
  if (!o.csv.empty()) writeCsv(o.csv, header, cols);

  std::printf("profile: %zu samples every %g m over %.1f m\n", p.s.size(), step, line.length());
  for (size_t k = 0; k < p.values.size(); ++k) {
    double mx = -INFINITY, at = NAN;
    for (size_t i = 0; i < p.s.size(); ++i)
      if (p.values[k][i] > mx) mx = p.values[k][i], at = p.s[i];
    std::printf("  %-36s max %s at %s m\n", header[3 + k].c_str(), num(mx).c_str(), num(at, "%.1f").c_str());
  }
  if (!o.plot.empty()) {
    std::vector<ChartLine> lines;
    if (!o.ground.empty()) {
      lines.push_back({"ground", p.values[0]});
      for (size_t k = 0; k < labels.size(); ++k) {
        ChartLine l{"ground + " + labels[k], {}};
        for (size_t i = 0; i < p.s.size(); ++i) l.y.push_back(p.values[0][i] + p.values[k + 1][i]);
        lines.push_back(l);
      }
    } else {
      for (size_t k = 0; k < labels.size(); ++k) lines.push_back({labels[k], p.values[k]});
    }
    writeLineChart(o.plot, o.title.empty() ? "Profile" : o.title, "distance along the line (m)",
                   o.ground.empty() ? "value" : "elevation (m)", p.s, lines);
    std::printf("  plot: %s\n", o.plot.c_str());
  }
  if (!o.csv.empty()) std::printf("  table: %s\n", o.csv.c_str());
  return 0;
}

std::vector<double> thresholdsOr(const std::vector<double>& t, double fallback) {
  return t.empty() ? std::vector<double>{fallback} : t;
}

int runMapStats(const AnalysisOptions& o) {
  if (o.aimec) return runAimecMapStats(o);
  const DemRaster r = readRaster(o.rasters.at(0));
  DemRaster ground;
  if (!o.ground.empty()) ground = readRaster(o.ground);
  Polyline path;
  if (!o.path.empty()) path = Polyline::parse(o.path);
  std::printf("%s: %d x %d cells of %g m\n", o.rasters[0].c_str(), r.grid.nx, r.grid.ny, r.grid.cellSize);
  std::printf("%10s %9s %12s %10s %10s %13s %12s %12s %10s\n", "threshold", "cells", "area_m2", "max", "mean",
              "volume_m3", "ground_min", "ground_max", "runout_m");
  for (double t : thresholdsOr(o.thresholds, 0)) {
    const MapStats m = mapStats(r, t, o.ground.empty() ? nullptr : &ground, o.path.empty() ? nullptr : &path, o.halfWidth);
    std::printf("%10g %9zu %12.0f %10s %10s %13.0f %12s %12s %10s%s\n", t, m.cells, m.area, num(m.max).c_str(),
                num(m.mean).c_str(), m.volume, num(m.groundMin, "%.1f").c_str(), num(m.groundMax, "%.1f").c_str(),
                num(m.runout, "%.1f").c_str(), m.runoutBeyondEnd ? " (beyond the path's end)" : "");
  }
  return 0;
}

int runCompare(const AnalysisOptions& o) {
  if (o.aimec) return runAimecCompare(o);
  const DemRaster simRaw = readRaster(o.simulation);
  const DemRaster ref = readRaster(o.reference);
  const DemRaster sim = resample(simRaw, ref.grid);
  Polyline path;
  if (!o.path.empty()) path = Polyline::parse(o.path);
  std::printf("simulation %s (%d x %d cells of %g m), resampled bilinearly onto\n", o.simulation.c_str(), simRaw.grid.nx,
              simRaw.grid.ny, simRaw.grid.cellSize);
  std::printf("reference  %s (%d x %d cells of %g m); cells without data in either are skipped\n", o.reference.c_str(),
              ref.grid.nx, ref.grid.ny, ref.grid.cellSize);
  std::printf("%9s %11s %11s %11s %8s %9s %9s %9s %9s %10s %10s %9s %8s %8s\n", "threshold", "area_sim", "area_ref",
              "area_both", "overlap", "max_sim", "max_ref", "mean_sim", "mean_ref", "runout_sim", "runout_ref",
              "d_runout", "bias", "rmse");
  const auto ts = thresholdsOr(o.thresholds, 0);
  for (double t : ts) {
    const Comparison c = compare(sim, ref, t, o.path.empty() ? nullptr : &path, o.halfWidth);
    std::printf("%9g %11.0f %11.0f %11.0f %8s %9s %9s %9s %9s %10s %10s %9s %8s %8s\n", t, c.sim.area, c.ref.area,
                c.areaBoth, num(c.overlap, "%.3f").c_str(), num(c.sim.max, "%.4g").c_str(), num(c.ref.max, "%.4g").c_str(),
                num(c.sim.mean, "%.4g").c_str(), num(c.ref.mean, "%.4g").c_str(), num(c.sim.runout, "%.1f").c_str(),
                num(c.ref.runout, "%.1f").c_str(), num(c.sim.runout - c.ref.runout, "%+.1f").c_str(),
                num(c.bias, "%+.3g").c_str(), num(c.rmse, "%.3g").c_str());
  }
  if (!o.png.empty()) {
    std::vector<float> heights;
    if (!o.dem.empty()) heights = resample(readRaster(o.dem), ref.grid).height;
    QuicklookStyle st;
    st.title = o.title.empty() ? "Simulation against reference" : o.title;
    char sub[160];
    std::snprintf(sub, sizeof sub, "cells reaching %g: %s", ts.front(), defaultLabel(o.simulation).c_str());
    st.subtitle = sub;
    st.classes = {{"reference only", {0.17, 0.45, 0.80}}, {"both", {0.45, 0.25, 0.55}}, {"Talus only", {0.85, 0.25, 0.15}}};
    writeMapQuicklook(o.png, ref.grid, overlapClasses(sim, ref, ts.front()), heights, st, -9999);
    std::printf("overlap map: %s\n", o.png.c_str());
  }
  return 0;
}

int runSeriesStats(const AnalysisOptions& o) {
  const SeriesTable t = readSeries(o.series);
  if (t.rows.empty()) throw std::runtime_error(o.series + ": no rows");
  auto peak = [&](size_t c, double& at) {
    double m = -INFINITY;
    at = NAN;
    for (const auto& r : t.rows)
      if (r[c] > m) m = r[c], at = r[0];
    return m;
  };
  auto starts = [](const std::string& s, const std::string& p) { return s.rfind(p, 0) == 0; };
  std::printf("%s: %zu rows, t = %g .. %g s\n", o.series.c_str(), t.rows.size(), t.rows.front()[0], t.rows.back()[0]);
  std::string keTotal;
  for (size_t c = 0; c < t.header.size(); ++c) {
    const std::string& h = t.header[c];
    double at = NAN;
    if (starts(h, "kinetic_energy_J_")) {
      const double m = peak(c, at);
      std::printf("  peak %-40s %12.5g J at %.2f s\n", h.c_str(), m, at);
      if (keTotal.empty() || h == "kinetic_energy_J_total") keTotal = h;
    } else if (h == "max_speed_m_s") {
      const double m = peak(c, at);
      std::printf("  peak %-40s %12.4g m/s at %.2f s\n", h.c_str(), m, at);
    } else if (starts(h, "probe_speed_m_s_")) {
      const double m = peak(c, at);
      std::printf("  peak %-40s %12.4g m/s at %.2f s\n", h.c_str(), m, at);
      const std::string name = h.substr(16);
      const int cx = t.column("probe_x_m_" + name), cy = t.column("probe_y_m_" + name), cz = t.column("probe_z_m_" + name);
      if (cx >= 0 && cy >= 0 && cz >= 0) {
        const auto& a = t.rows.front();
        const auto& b = t.rows.back();
        const double d = std::sqrt(std::pow(b[size_t(cx)] - a[size_t(cx)], 2) + std::pow(b[size_t(cy)] - a[size_t(cy)], 2) +
                                   std::pow(b[size_t(cz)] - a[size_t(cz)], 2));
        std::printf("       probe %s moved %.1f m (drop %.1f m)\n", name.c_str(), d, a[size_t(cz)] - b[size_t(cz)]);
      }
    } else if (starts(h, "discharge_m3_s_")) {
      const double m = peak(c, at);
      // Rows are means over the interval before them: the volume is their sum times the intervals.
      double vol = 0;
      for (size_t i = 1; i < t.rows.size(); ++i) vol += t.rows[i][c] * (t.rows[i][0] - t.rows[i - 1][0]);
      std::printf("  peak %-40s %12.5g m3/s at %.2f s, volume %.5g m3\n", h.c_str(), m, at, vol);
    } else if (h == "max_water_surface_m") {
      const double m = peak(c, at);
      std::printf("  highest water surface %.2f m at %.2f s (start %.2f m, rise %.2f m)\n", m, at, t.rows.front()[c],
                  m - t.rows.front()[c]);
    } else if (starts(h, "front_m_")) {
      const double m = peak(c, at);
      std::printf("  farthest %-36s %12.1f m at %.2f s (end %.1f m)\n", h.c_str(), m, at, t.rows.back()[c]);
    }
  }
  if (!keTotal.empty()) {
    const double rest = timeBelowFraction(t, keTotal, o.restFraction);
    if (std::isfinite(rest))
      std::printf("  at rest (%s below %g of its peak from then on) at %.2f s\n", keTotal.c_str(), o.restFraction, rest);
    else
      std::printf("  not at rest by the end (%s stays above %g of its peak)\n", keTotal.c_str(), o.restFraction);
  }
  // Front speed against distance, every path.
  std::vector<std::string> paths;
  for (const auto& h : t.header)
    if (starts(h, "front_m_")) paths.push_back(h.substr(8));
  if (paths.empty()) return 0;
  std::vector<FrontSpeed> fs;
  size_t longest = 0;
  for (const auto& p : paths) {
    fs.push_back(frontSpeedAgainstDistance(t, p, o.frontStep, o.frontWindow));
    longest = std::max(longest, fs.back().s.size());
    double m = -INFINITY, at = NAN;
    for (size_t i = 0; i < fs.back().s.size(); ++i)
      if (fs.back().speed[i] > m) m = fs.back().speed[i], at = fs.back().s[i];
    if (std::isfinite(m))
      std::printf("  front speed along %-28s max %.1f m/s at %.0f m (window +-%g m)\n", p.c_str(), m, at, o.frontWindow);
  }
  std::vector<double> s;
  for (size_t i = 0; i < longest; ++i) s.push_back(double(i) * o.frontStep);
  std::vector<ChartLine> lines;
  std::vector<std::string> header{"distance_m"};
  std::vector<std::vector<double>> cols{s};
  for (size_t k = 0; k < paths.size(); ++k) {
    std::vector<double> v(longest, NAN), a(longest, NAN);
    for (size_t i = 0; i < fs[k].s.size(); ++i) v[i] = fs[k].speed[i], a[i] = fs[k].arrival[i];
    lines.push_back({paths[k], v});
    header.push_back("arrival_s_" + paths[k]);
    header.push_back("front_speed_m_s_" + paths[k]);
    cols.push_back(a);
    cols.push_back(v);
  }
  if (!o.frontCsv.empty()) writeCsv(o.frontCsv, header, cols);
  if (!o.frontPlot.empty()) {
    char title[128];
    std::snprintf(title, sizeof title, "Front speed against distance (over +-%g m)", o.frontWindow);
    writeLineChart(o.frontPlot, o.title.empty() ? title : o.title, "distance along the path (m)", "front speed (m/s)", s,
                   lines);
    std::printf("  plot: %s\n", o.frontPlot.c_str());
  }
  return 0;
}

} // namespace

AnalysisCommands addAnalysisCommands(CLI::App& app, AnalysisOptions& o) {
  AnalysisCommands c;
  c.profile = app.add_subcommand("profile", "Sample map rasters along a polyline: CSV table and PNG plot");
  c.profile->add_option("rasters", o.rasters, "Rasters (GeoTIFF maps, any raster GDAL reads)")->required();
  c.profile->add_option("--line", o.line, "Polyline \"x,y x,y ...\" (world, m) or a vector file with a line")->required();
  c.profile->add_option("--ground", o.ground,
                        "Ground elevation raster (maps/ground_elevation.tif): the plot then shows ground + each raster");
  c.profile->add_option("--step", o.step, "Sample spacing (m); default: the first raster's cell size")
      ->check(CLI::PositiveNumber);
  c.profile->add_option("--label", o.labels, "Labels of the rasters, in order (default: from the file names)");
  c.profile->add_option("--out", o.csv, "CSV table to write");
  c.profile->add_option("--plot", o.plot, "PNG plot to write");
  c.profile->add_option("--title", o.title, "Plot title");

  c.mapStats = app.add_subcommand("map-stats", "Area, mean, volume, ground elevations and run-out of one map");
  c.mapStats->add_option("raster", o.rasters, "A map raster")->required()->expected(1);
  c.mapStats->add_option("--threshold", o.thresholds, "Cells at or above this value count (repeatable; default > 0)");
  c.mapStats->add_option("--ground", o.ground, "Ground elevation raster: lowest and highest ground reached");
  c.mapStats->add_option("--path", o.path, "Path \"x,y x,y ...\" or a line file: run-out along it");
  c.mapStats->add_option("--half-width", o.halfWidth, "Only cells this close to the path count for the run-out (m)")
      ->check(CLI::PositiveNumber);

  c.compare = app.add_subcommand("compare", "Compare a simulated map with a reference raster on the reference's grid");
  c.compare->add_option("simulation", o.simulation, "Simulated map raster")->required();
  c.compare->add_option("reference", o.reference, "Reference raster (e.g. AvaFrame *_pft.asc)")->required();
  c.compare->add_option("--threshold", o.thresholds, "Thresholds (repeatable; default > 0)");
  c.compare->add_option("--path", o.path, "Path \"x,y x,y ...\" or a line file: run-out along it");
  c.compare->add_option("--half-width", o.halfWidth, "Only cells this close to the path count for the run-out (m)")
      ->check(CLI::PositiveNumber);
  c.compare->add_option("--png", o.png, "Overlap map (PNG) at the first threshold");
  c.compare->add_option("--dem", o.dem, "DEM for the overlap map's hillshade");
  c.compare->add_option("--title", o.title, "Overlap map title");

  addAimecOptions(c.mapStats, c.compare, o);

  c.seriesStats = app.add_subcommand("series-stats", "Peaks, time to rest, discharged volumes and front speeds of series.csv");
  c.seriesStats->add_option("series", o.series, "series.csv of a run")->required();
  c.seriesStats->add_option("--rest-fraction", o.restFraction,
                            "At rest once the total kinetic energy stays below this fraction of its peak")
      ->check(CLI::Range(0.0, 1.0));
  c.seriesStats->add_option("--front-step", o.frontStep, "Distance step of the front speed table (m)")
      ->check(CLI::PositiveNumber);
  c.seriesStats->add_option("--front-window", o.frontWindow, "Front speed over +-this distance (m)")
      ->check(CLI::PositiveNumber);
  c.seriesStats->add_option("--front-plot", o.frontPlot, "PNG of front speed against distance, every path");
  c.seriesStats->add_option("--front-csv", o.frontCsv, "CSV of front arrival time and speed against distance");
  c.seriesStats->add_option("--title", o.title, "Front plot title");
  return c;
}

int runAnalysisCommand(const AnalysisCommands& c, const AnalysisOptions& o) {
  if (*c.profile) return runProfile(o);
  if (*c.mapStats) return runMapStats(o);
  if (*c.compare) return runCompare(o);
  if (*c.seriesStats) return runSeriesStats(o);
  return -1;
}

} // namespace talus
