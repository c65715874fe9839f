#include "io/common/chart_drawing.h"

#include "io/common/atomic_file.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace talus::chart {

std::vector<double> niceTicks(double lo, double hi, int count, double* stepOut) {
  std::vector<double> ticks;
  if (!(hi > lo) || !std::isfinite(lo) || !std::isfinite(hi)) {
    if (stepOut) *stepOut = 1;
    return {lo};
  }
  const double raw = (hi - lo) / std::max(1, count);
  const double mag = std::pow(10.0, std::floor(std::log10(raw)));
  double step = mag;
  for (double m : {1.0, 2.0, 2.5, 5.0, 10.0})
    if (m * mag >= raw) {
      step = m * mag;
      break;
    }
  for (double t = std::ceil(lo / step - 1e-9) * step; t <= hi + 1e-9 * step; t += step)
    ticks.push_back(std::abs(t) < 1e-12 * step ? 0.0 : t);
  if (stepOut) *stepOut = step;
  return ticks;
}

double niceCeil(double v) {
  if (!(v > 0) || !std::isfinite(v)) return 1;
  const double mag = std::pow(10.0, std::floor(std::log10(v)));
  for (double m : {1.0, 1.5, 2.0, 2.5, 3.0, 4.0, 5.0, 6.0, 8.0, 10.0})
    if (m * mag >= v * (1 - 1e-12)) return m * mag;
  return 10 * mag;
}

std::string tickLabel(double value, double step) {
  char buf[64];
  const double a = std::abs(step);
  if (a >= 1e5 || (a > 0 && a < 1e-4)) {
    std::snprintf(buf, sizeof buf, "%.3g", value);
  } else {
    int decimals = 0;
    while (decimals < 6 && std::abs(step * std::pow(10.0, decimals) - std::round(step * std::pow(10.0, decimals))) > 1e-6)
      ++decimals;
    std::snprintf(buf, sizeof buf, "%.*f", decimals, value);
  }
  return buf;
}

void text(cairo_t* cr, double x, double y, const std::string& s, double size, Align h, Align v, bool bold) {
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, bold ? CAIRO_FONT_WEIGHT_BOLD : CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, size);
  cairo_text_extents_t e;
  cairo_text_extents(cr, s.c_str(), &e);
  double px = x - e.x_bearing;
  if (h == Align::Centre) px = x - e.x_bearing - 0.5 * e.width;
  if (h == Align::End) px = x - e.x_bearing - e.width;
  // Vertical placement on the font's cap height, so labels of different glyphs line up.
  const double cap = 0.72 * size;
  double py = y;
  if (v == Align::Centre) py = y + 0.5 * cap;
  if (v == Align::Start) py = y + cap;
  cairo_move_to(cr, px, py);
  cairo_show_text(cr, s.c_str());
}

void textRotated(cairo_t* cr, double x, double y, const std::string& s, double size) {
  cairo_save(cr);
  cairo_translate(cr, x, y);
  cairo_rotate(cr, -M_PI / 2);
  text(cr, 0, 0, s, size, Align::Centre, Align::Centre);
  cairo_restore(cr);
}

namespace {
struct Stop {
  double t;
  Rgb c;
};
Rgb interpolate(const std::vector<Stop>& stops, double t) {
  t = std::clamp(t, 0.0, 1.0);
  for (size_t i = 1; i < stops.size(); ++i)
    if (t <= stops[i].t) {
      const double u = (t - stops[i - 1].t) / (stops[i].t - stops[i - 1].t);
      const Rgb& a = stops[i - 1].c;
      const Rgb& b = stops[i].c;
      return {a.r + u * (b.r - a.r), a.g + u * (b.g - a.g), a.b + u * (b.b - a.b)};
    }
  return stops.back().c;
}
} // namespace

Rgb ramp(Ramp which, double t) {
  // Control points sampled from matplotlib's viridis/magma/plasma and ColorBrewer Blues/YlOrBr.
  static const std::vector<Stop> viridis = {{0.0, {0.267, 0.005, 0.329}}, {0.25, {0.229, 0.322, 0.546}},
                                            {0.5, {0.128, 0.567, 0.551}}, {0.75, {0.369, 0.789, 0.383}},
                                            {1.0, {0.993, 0.906, 0.144}}};
  static const std::vector<Stop> magma = {{0.0, {0.001, 0.000, 0.014}}, {0.25, {0.317, 0.071, 0.485}},
                                          {0.5, {0.716, 0.215, 0.475}}, {0.75, {0.987, 0.535, 0.382}},
                                          {1.0, {0.987, 0.991, 0.750}}};
  static const std::vector<Stop> plasma = {{0.0, {0.050, 0.030, 0.528}}, {0.25, {0.494, 0.012, 0.658}},
                                           {0.5, {0.798, 0.280, 0.470}}, {0.75, {0.973, 0.585, 0.253}},
                                           {1.0, {0.940, 0.975, 0.131}}};
  static const std::vector<Stop> blues = {{0.0, {0.871, 0.922, 0.969}}, {0.33, {0.620, 0.792, 0.882}},
                                          {0.66, {0.259, 0.573, 0.776}}, {1.0, {0.031, 0.188, 0.420}}};
  static const std::vector<Stop> browns = {{0.0, {1.000, 0.969, 0.737}}, {0.33, {0.996, 0.769, 0.310}},
                                           {0.66, {0.851, 0.373, 0.055}}, {1.0, {0.400, 0.145, 0.024}}};
  switch (which) {
  case Ramp::Viridis: return interpolate(viridis, t);
  case Ramp::Magma: return interpolate(magma, t);
  case Ramp::Plasma: return interpolate(plasma, t);
  case Ramp::Blues: return interpolate(blues, t);
  case Ramp::Browns: return interpolate(browns, t);
  }
  return interpolate(viridis, t);
}

Rgb lineColour(int i) {
  static const Rgb tab10[10] = {{0.122, 0.467, 0.706}, {1.000, 0.498, 0.055}, {0.173, 0.627, 0.173},
                                {0.839, 0.153, 0.157}, {0.580, 0.404, 0.741}, {0.549, 0.337, 0.294},
                                {0.890, 0.467, 0.761}, {0.498, 0.498, 0.498}, {0.737, 0.741, 0.133},
                                {0.090, 0.745, 0.812}};
  return tab10[((i % 10) + 10) % 10];
}

void writePng(cairo_surface_t* surface, const std::string& path) {
  // Encoded in memory: cairo's file writer reports a full disk only as "error while writing".
  std::string png;
  const cairo_status_t st = cairo_surface_write_to_png_stream(
      surface,
      [](void* out, const unsigned char* data, unsigned int n) {
        static_cast<std::string*>(out)->append(reinterpret_cast<const char*>(data), n);
        return CAIRO_STATUS_SUCCESS;
      },
      &png);
  if (st != CAIRO_STATUS_SUCCESS) throw WriteError(path, cairo_status_to_string(st));
  writeAtomically(path, [&](const std::string& tmp) { writeFileBytes(tmp, png); });
}

} // namespace talus::chart
