#include "tools/work_precision_plot.h"

#include "io/common/chart_drawing.h"

#include <algorithm>
#include <cairo.h>
#include <cmath>
#include <memory>
#include <sstream>

namespace talus::work_precision {

namespace {
/// A tick's label: a power of ten as %g prints it (0.01, 1, 1e-05).
std::string decade(double d) {
  std::ostringstream o;
  o << d;
  return o.str();
}
} // namespace

/// Log-log chart: one polyline per case through its (wall, error) points.
void plot(const std::string& path, const std::vector<std::string>& names, const std::vector<std::vector<Point>>& series) {
  const int W = 900, H = 600, L = 90, R = 230, T = 50, B = 70;
  double x0 = 1e300, x1 = 0, y0 = 1e300, y1 = 0;
  for (const auto& s : series)
    for (const auto& p : s) {
      if (!(p.wall > 0) || !(p.error > 0)) continue;
      x0 = std::min(x0, p.wall), x1 = std::max(x1, p.wall), y0 = std::min(y0, p.error), y1 = std::max(y1, p.error);
    }
  if (!(x1 > 0)) return;
  x0 = std::pow(10, std::floor(std::log10(x0))), x1 = std::pow(10, std::ceil(std::log10(x1)));
  y0 = std::pow(10, std::floor(std::log10(y0))), y1 = std::pow(10, std::ceil(std::log10(y1)));
  auto X = [&](double v) { return L + (W - L - R) * (std::log10(v) - std::log10(x0)) / (std::log10(x1) - std::log10(x0)); };
  auto Y = [&](double v) { return H - B - (H - T - B) * (std::log10(v) - std::log10(y0)) / (std::log10(y1) - std::log10(y0)); };
  std::unique_ptr<cairo_surface_t, decltype(&cairo_surface_destroy)> surf(
      cairo_image_surface_create(CAIRO_FORMAT_RGB24, W, H), cairo_surface_destroy);
  std::unique_ptr<cairo_t, decltype(&cairo_destroy)> cr(cairo_create(surf.get()), cairo_destroy);
  cairo_set_source_rgb(cr.get(), 1, 1, 1);
  cairo_paint(cr.get());
  cairo_set_line_width(cr.get(), 1);
  for (double d = x0; d <= x1 * 1.0001; d *= 10) { // decades
    cairo_set_source_rgb(cr.get(), 0.85, 0.85, 0.85);
    cairo_move_to(cr.get(), X(d), T), cairo_line_to(cr.get(), X(d), H - B), cairo_stroke(cr.get());
    cairo_set_source_rgb(cr.get(), 0, 0, 0);
    chart::text(cr.get(), X(d), H - B + 18, decade(d), 12, chart::Align::Centre);
  }
  for (double d = y0; d <= y1 * 1.0001; d *= 10) {
    cairo_set_source_rgb(cr.get(), 0.85, 0.85, 0.85);
    cairo_move_to(cr.get(), L, Y(d)), cairo_line_to(cr.get(), W - R, Y(d)), cairo_stroke(cr.get());
    cairo_set_source_rgb(cr.get(), 0, 0, 0);
    chart::text(cr.get(), L - 6, Y(d), decade(d), 12, chart::Align::End, chart::Align::Centre);
  }
  cairo_set_source_rgb(cr.get(), 0, 0, 0);
  cairo_rectangle(cr.get(), L, T, W - L - R, H - T - B), cairo_stroke(cr.get());
  chart::text(cr.get(), (L + W - R) / 2.0, H - 25, "wall time (s, 2 threads)", 14, chart::Align::Centre);
  chart::textRotated(cr.get(), 25, (T + H - B) / 2.0, "relative error", 14);
  chart::text(cr.get(), L, 30, "Talus: error against cost, each case refined at fixed particles per cell and CFL", 15,
              chart::Align::Start, chart::Align::End, true);
  for (size_t i = 0; i < series.size(); ++i) {
    const chart::Rgb c = chart::lineColour(int(i));
    cairo_set_source_rgb(cr.get(), c.r, c.g, c.b);
    cairo_set_line_width(cr.get(), 2);
    bool first = true;
    for (const auto& p : series[i]) {
      if (!(p.wall > 0) || !(p.error > 0)) continue;
      if (first) cairo_move_to(cr.get(), X(p.wall), Y(p.error));
      else cairo_line_to(cr.get(), X(p.wall), Y(p.error));
      first = false;
    }
    cairo_stroke(cr.get());
    for (const auto& p : series[i])
      if (p.wall > 0 && p.error > 0) {
        cairo_arc(cr.get(), X(p.wall), Y(p.error), 4, 0, 2 * M_PI);
        cairo_fill(cr.get());
      }
    const double ly = T + 20 + 24 * double(i);
    cairo_rectangle(cr.get(), W - R + 15, ly - 6, 20, 4), cairo_fill(cr.get());
    cairo_set_source_rgb(cr.get(), 0, 0, 0);
    chart::text(cr.get(), W - R + 42, ly, names[i], 13, chart::Align::Start, chart::Align::Centre);
  }
  chart::writePng(surf.get(), path);
}

} // namespace talus::work_precision
