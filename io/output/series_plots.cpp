#include "io/output/series_plots.h"

#include "io/common/chart_drawing.h"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>

namespace talus {

using chart::Align;

void writeLineChart(const std::string& path, const std::string& title, const std::string& xLabel,
                    const std::string& yLabel, const std::vector<double>& x, const std::vector<ChartLine>& lines) {
  cairo_surface_t* s = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 1, 1);
  cairo_t* cr = cairo_create(s);
  // The legend sits right of the plot, so it never hides a line.
  const bool legend = lines.size() > 1 || (lines.size() == 1 && !lines[0].label.empty());
  double legendW = 0;
  if (legend) {
    cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(cr, 12);
    for (const auto& l : lines) {
      cairo_text_extents_t e;
      cairo_text_extents(cr, l.label.c_str(), &e);
      legendW = std::max(legendW, e.x_advance + 44);
    }
  }
  cairo_destroy(cr);
  cairo_surface_destroy(s);

  const double pw = 720, ph = 400, L = 90, R = 24 + (legend ? legendW + 12 : 0), T = 56, B = 64;
  const int W = int(L + pw + R), H = int(T + ph + B);
  double x0 = x.empty() ? 0 : x.front(), x1 = x.empty() ? 1 : x.back();
  double y0 = std::numeric_limits<double>::infinity(), y1 = -y0;
  for (const auto& l : lines)
    for (double v : l.y)
      if (std::isfinite(v)) y0 = std::min(y0, v), y1 = std::max(y1, v);
  if (!(y1 >= y0)) y0 = 0, y1 = 1;
  if (y1 - y0 < 1e-12 * std::max(1.0, std::abs(y1))) y0 -= 0.5 * std::max(1.0, std::abs(y0)), y1 += 0.5 * std::max(1.0, std::abs(y1));
  if (!(x1 > x0)) x1 = x0 + 1;
  double ystep = 1, xstep = 1;
  chart::niceTicks(y0, y1, 6, &ystep);
  // Extend the y range to whole ticks so lines never run along the frame.
  y0 = std::floor(y0 / ystep + 1e-9) * ystep, y1 = std::ceil(y1 / ystep - 1e-9) * ystep;
  const auto yt = chart::niceTicks(y0, y1, 6, &ystep);
  const auto xt = chart::niceTicks(x0, x1, 8, &xstep);
  auto px = [&](double v) { return L + pw * (v - x0) / (x1 - x0); };
  auto py = [&](double v) { return T + ph * (1 - (v - y0) / (y1 - y0)); };

  s = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, W, H);
  cr = cairo_create(s);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  // Grid and ticks.
  cairo_set_line_width(cr, 1);
  for (double t : yt) {
    cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
    cairo_move_to(cr, L, std::round(py(t)) + 0.5);
    cairo_line_to(cr, L + pw, std::round(py(t)) + 0.5);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    chart::text(cr, L - 8, py(t), chart::tickLabel(t, ystep), 12, Align::End, Align::Centre);
  }
  for (double t : xt) {
    if (t < x0 - 1e-9 * xstep || t > x1 + 1e-9 * xstep) continue;
    cairo_set_source_rgb(cr, 0.9, 0.9, 0.9);
    cairo_move_to(cr, std::round(px(t)) + 0.5, T);
    cairo_line_to(cr, std::round(px(t)) + 0.5, T + ph);
    cairo_stroke(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    chart::text(cr, px(t), T + ph + 8, chart::tickLabel(t, xstep), 12, Align::Centre, Align::Start);
  }
  cairo_set_source_rgb(cr, 0, 0, 0);
  cairo_rectangle(cr, L + 0.5, T + 0.5, pw, ph);
  cairo_stroke(cr);
  chart::text(cr, L, 32, title, 18, Align::Start, Align::End, true);
  chart::text(cr, L + pw / 2, H - 14, xLabel, 13, Align::Centre, Align::End);
  chart::textRotated(cr, 22, T + ph / 2, yLabel, 13);

  // Past ten lines the colours repeat, dashed.
  auto pen = [&](size_t i) {
    const chart::Rgb c = chart::lineColour(int(i));
    cairo_set_source_rgb(cr, c.r, c.g, c.b);
    const double dash[] = {6, 4};
    cairo_set_dash(cr, dash, i >= 10 ? 2 : 0, 0);
  };
  cairo_save(cr);
  cairo_rectangle(cr, L, T, pw, ph);
  cairo_clip(cr);
  cairo_set_line_width(cr, 2);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  for (size_t i = 0; i < lines.size(); ++i) {
    pen(i);
    if (lines[i].points) {
      for (size_t k = 0; k < x.size() && k < lines[i].y.size(); ++k)
        if (std::isfinite(lines[i].y[k])) {
          cairo_new_sub_path(cr);
          cairo_arc(cr, px(x[k]), py(lines[i].y[k]), 4, 0, 2 * M_PI);
        }
      cairo_fill(cr);
      continue;
    }
    bool down = false;
    for (size_t k = 0; k < x.size() && k < lines[i].y.size(); ++k) {
      const double v = lines[i].y[k];
      if (!std::isfinite(v)) {
        down = false;
        continue;
      }
      if (!down) {
        cairo_move_to(cr, px(lines[i].steps && k > 0 ? x[k - 1] : x[k]), py(v));
        if (lines[i].steps && k > 0) cairo_line_to(cr, px(x[k]), py(v));
        down = true;
        continue;
      }
      if (lines[i].steps) cairo_line_to(cr, px(x[k - 1]), py(v));
      cairo_line_to(cr, px(x[k]), py(v));
    }
    cairo_stroke(cr);
  }
  cairo_restore(cr);

  if (legend) {
    const double lx = L + pw + 12, ly = T;
    for (size_t i = 0; i < lines.size(); ++i) {
      const double yy = ly + 8 + 18.0 * i;
      pen(i);
      cairo_set_line_width(cr, 2);
      cairo_move_to(cr, lx, yy);
      cairo_line_to(cr, lx + 24, yy);
      cairo_stroke(cr);
      cairo_set_source_rgb(cr, 0, 0, 0);
      chart::text(cr, lx + 30, yy, lines[i].label, 12, Align::Start, Align::Centre);
    }
  }
  cairo_destroy(cr);
  try {
    chart::writePng(s, path);
  } catch (...) {
    cairo_surface_destroy(s);
    throw;
  }
  cairo_surface_destroy(s);
}

namespace {

std::vector<double> columnValues(const SeriesTable& t, int c) {
  std::vector<double> v;
  for (const auto& r : t.rows) v.push_back(r[size_t(c)]);
  return v;
}

/// Lines for every column whose name starts with `prefix`, labelled by the rest of the name.
std::vector<ChartLine> byPrefix(const SeriesTable& t, const std::string& prefix, const std::string& labelPrefix = "") {
  std::vector<ChartLine> out;
  for (size_t c = 0; c < t.header.size(); ++c)
    if (t.header[c].rfind(prefix, 0) == 0) {
      std::string rest = t.header[c].substr(prefix.size());
      if (!rest.empty() && rest[0] == '_') rest = rest.substr(1);
      out.push_back({labelPrefix + rest, columnValues(t, int(c))});
    }
  return out;
}

} // namespace

std::vector<std::string> writeSeriesPlots(const std::string& outDir, const SeriesTable& t) {
  namespace fs = std::filesystem;
  std::vector<std::string> files;
  if (t.rows.size() < 2) return files;
  fs::create_directories(fs::path(outDir) / "plots");
  const std::vector<double> time = columnValues(t, 0);
  auto plot = [&](const std::string& name, const std::string& title, const std::string& yLabel,
                  const std::vector<ChartLine>& lines) {
    if (lines.empty()) return;
    const std::string rel = "plots/" + name + ".png";
    writeLineChart((fs::path(outDir) / rel).string(), title, "time (s)", yLabel, time, lines);
    files.push_back(rel);
  };

  // Energy: kinetic per material, potential change, and their sum (what is left of the
  // initial energy after dissipation, relative to the start).
  std::vector<ChartLine> energy = byPrefix(t, "kinetic_energy_J", "kinetic ");
  const int pe = t.column("potential_energy_J");
  if (pe >= 0) {
    energy.push_back({"potential (change)", columnValues(t, pe)});
    int ke = t.column("kinetic_energy_J_total");
    if (ke < 0)
      for (size_t c = 0; c < t.header.size(); ++c)
        if (t.header[c].rfind("kinetic_energy_J_", 0) == 0) ke = int(c);
    if (ke >= 0) {
      ChartLine sum{"kinetic + potential", {}};
      for (const auto& r : t.rows) sum.y.push_back(r[size_t(ke)] + r[size_t(pe)]);
      energy.push_back(sum);
    }
  }
  plot("energy", "Energy", "energy (J)", energy);
  // Kinetic energy alone: the potential change dwarfs it in the plot above.
  plot("kinetic_energy", "Kinetic energy per material", "kinetic energy (J)", byPrefix(t, "kinetic_energy_J"));
  std::vector<ChartLine> mass = byPrefix(t, "mass_kg");
  const int removed = t.column("mass_removed_kg");
  if (removed >= 0) mass.push_back({"removed (left the domain)", columnValues(t, removed)});
  plot("mass", "Mass in the domain", "mass (kg)", mass);
  plot("speed", "Maximum particle speed", "speed (m/s)", byPrefix(t, "max_speed_m_s"));
  // Discharge rows are means over the interval before them: drawn as steps.
  std::vector<ChartLine> discharge = byPrefix(t, "discharge_m3_s");
  for (auto& l : discharge) l.steps = true;
  plot("discharge", "Discharge through sections (mean over each row's interval)", "discharge (m\u00b3/s)", discharge);
  plot("front", "Front position along paths", "distance along path (m)", byPrefix(t, "front_m"));
  plot("front_speed", "Front speed along paths", "speed (m/s)", byPrefix(t, "front_speed_m_s"));
  plot("probe_speed", "Speed at probes (moving with the flow)", "speed (m/s)", byPrefix(t, "probe_speed_m_s"));
  // Loads on colliders, in kN: the mean over each row's interval (steps) and its largest step.
  auto kiloNewton = [](std::vector<ChartLine> lines, bool steps) {
    for (auto& l : lines) {
      for (double& y : l.y) y *= 1e-3;
      l.steps = steps;
    }
    return lines;
  };
  plot("loads", "Force on colliders (mean over each row's interval)", "force (kN)", kiloNewton(byPrefix(t, "force_N"), true));
  plot("max_loads", "Largest force of a step on colliders", "force (kN)", kiloNewton(byPrefix(t, "max_force_N"), true));
  plot("water_surface", "Highest water surface", "elevation (m)", byPrefix(t, "max_water_surface_m"));
  plot("gauges", "Water surface at the gauges", "elevation (m)", byPrefix(t, "water_surface_m_"));
  return files;
}

} // namespace talus
