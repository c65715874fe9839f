#include "io/output/map_quicklook.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>

namespace talus {

using chart::Align;

std::vector<float> hillshade(const RasterGrid& g, const std::vector<float>& z) {
  std::vector<float> out(g.size(), std::numeric_limits<float>::quiet_NaN());
  if (z.size() != g.size()) return out;
  const double alt = 45 * M_PI / 180, az = 315 * M_PI / 180;
  const double lx = std::cos(alt) * std::sin(az), ly = std::cos(alt) * std::cos(az), lz = std::sin(alt);
  auto at = [&](int c, int r) -> double {
    if (c < 0 || r < 0 || c >= g.nx || r >= g.ny) return NAN; // edges: one-sided differences
    return z[g.index(c, r)];
  };
  for (int r = 0; r < g.ny; ++r)
    for (int c = 0; c < g.nx; ++c) {
      const double h = at(c, r);
      if (!std::isfinite(h)) continue;
      // Central differences, one-sided next to missing cells; y grows north, rows grow south.
      double e = at(c + 1, r), w = at(c - 1, r), n = at(c, r - 1), s = at(c, r + 1);
      double sx = 2 * g.cellSize, sy = 2 * g.cellSize;
      if (!std::isfinite(e)) e = h, sx -= g.cellSize;
      if (!std::isfinite(w)) w = h, sx -= g.cellSize;
      if (!std::isfinite(n)) n = h, sy -= g.cellSize;
      if (!std::isfinite(s)) s = h, sy -= g.cellSize;
      const double zx = sx > 0 ? (e - w) / sx : 0, zy = sy > 0 ? (n - s) / sy : 0;
      const double norm = std::sqrt(zx * zx + zy * zy + 1);
      out[g.index(c, r)] = float(std::max(0.0, (-zx * lx - zy * ly + lz) / norm));
    }
  return out;
}

namespace {

uint32_t argb(double a, double r, double g, double b) {
  auto q = [](double v) { return uint32_t(std::clamp(v, 0.0, 1.0) * 255 + 0.5); };
  // cairo's ARGB32 is premultiplied.
  return (q(a) << 24) | (q(r * a) << 16) | (q(g * a) << 8) | q(b * a);
}

std::string lengthLabel(double metres) {
  char buf[32];
  if (metres >= 1000) std::snprintf(buf, sizeof buf, "%g km", metres / 1000);
  else std::snprintf(buf, sizeof buf, "%g m", metres);
  return buf;
}

} // namespace

/// The quick-look's page (the caller destroys it).
static cairo_surface_t* drawPage(const RasterGrid& grid, const std::vector<float>& values,
                                 const std::vector<float>& shade, const QuicklookStyle& style, float nodata) {
  // Reduce large rasters by blocks of f x f cells (maximum for values, mean for the hillshade).
  const int f = std::max(1, int(std::ceil(std::max(grid.nx, grid.ny) / 900.0)));
  const int w = (grid.nx + f - 1) / f, h = (grid.ny + f - 1) / f;
  std::vector<float> val(size_t(w) * h, 0.f), sh(size_t(w) * h, std::numeric_limits<float>::quiet_NaN());
  std::vector<uint8_t> missing(size_t(w) * h, 1); // every cell of the block is no data
  float vmaxData = 0;
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      float vm = 0;
      double ss = 0;
      int sn = 0;
      for (int rr = r * f; rr < std::min(grid.ny, (r + 1) * f); ++rr)
        for (int cc = c * f; cc < std::min(grid.nx, (c + 1) * f); ++cc) {
          const float v = values[grid.index(cc, rr)];
          if (std::isfinite(v) && v != nodata) vm = std::max(vm, v), missing[size_t(r) * w + c] = 0;
          if (!shade.empty() && std::isfinite(shade[grid.index(cc, rr)])) ss += shade[grid.index(cc, rr)], ++sn;
        }
      val[size_t(r) * w + c] = vm;
      if (sn) sh[size_t(r) * w + c] = float(ss / sn);
      vmaxData = std::max(vmaxData, vm);
    }
  const double vmax = style.scaleMax > 0 ? style.scaleMax : chart::niceCeil(vmaxData);

  // The raster as an image: background (hillshade or flat grey) under the colour layer.
  cairo_surface_t* img = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, w, h);
  const int stride = cairo_image_surface_get_stride(img) / 4;
  uint32_t* px = reinterpret_cast<uint32_t*>(cairo_image_surface_get_data(img));
  for (int r = 0; r < h; ++r)
    for (int c = 0; c < w; ++c) {
      const float s = sh[size_t(r) * w + c];
      const double grey = std::isfinite(s) ? 0.25 + 0.7 * s : 0.88;
      const float v = val[size_t(r) * w + c];
      double R = grey, G = grey, B = grey;
      const int k = int(std::lround(v));
      const bool isClass = !style.classes.empty() && k >= 1 && k <= int(style.classes.size());
      if (v > 0 && (style.classes.empty() || isClass)) {
        const chart::Rgb col = isClass ? style.classes[size_t(k - 1)].second : chart::ramp(style.ramp, v / vmax);
        const double a = 0.85; // let the relief show through a little
        R = a * col.r + (1 - a) * grey, G = a * col.g + (1 - a) * grey, B = a * col.b + (1 - a) * grey;
      }
      if (missing[size_t(r) * w + c]) R = G = B = 1; // no data: the page shows through
      px[size_t(r) * stride + c] = argb(1, R, G, B);
    }
  cairo_surface_mark_dirty(img);

  // Page layout: map scaled to at most ~900 px, colour bar right, titles above, scale bar below.
  const double scale = std::min(900.0 / w, 900.0 / h);
  const double mapW = w * scale, mapH = h * scale;
  const double left = 24, top = 70, right = style.classes.empty() ? 130 : 150, bottom = 64;
  // A narrow map (a path grid, a gully) still gets a page as wide as its titles.
  double titleW = 0;
  {
    cairo_surface_t* probe = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, 1, 1);
    cairo_t* pc = cairo_create(probe);
    cairo_text_extents_t e;
    cairo_select_font_face(pc, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_BOLD);
    cairo_set_font_size(pc, 20);
    cairo_text_extents(pc, style.title.c_str(), &e);
    titleW = e.x_advance;
    cairo_select_font_face(pc, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
    cairo_set_font_size(pc, 13);
    cairo_text_extents(pc, (style.subtitle + "  (no flow in this map)").c_str(), &e);
    titleW = std::max(titleW, e.x_advance);
    cairo_destroy(pc);
    cairo_surface_destroy(probe);
  }
  const int W = int(std::ceil(std::max(left + mapW + right, left + titleW + 24))), H = int(std::ceil(top + mapH + bottom));
  cairo_surface_t* page = cairo_image_surface_create(CAIRO_FORMAT_ARGB32, W, H);
  cairo_t* cr = cairo_create(page);
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);

  cairo_save(cr);
  cairo_translate(cr, left, top);
  cairo_scale(cr, scale, scale);
  cairo_set_source_surface(cr, img, 0, 0);
  cairo_pattern_set_filter(cairo_get_source(cr), CAIRO_FILTER_NEAREST);
  cairo_rectangle(cr, 0, 0, w, h);
  cairo_fill(cr);
  cairo_restore(cr);
  cairo_set_source_rgb(cr, 0.2, 0.2, 0.2);
  cairo_set_line_width(cr, 1);
  cairo_rectangle(cr, left + 0.5, top + 0.5, mapW - 1, mapH - 1);
  cairo_stroke(cr);

  // Titles.
  cairo_set_source_rgb(cr, 0, 0, 0);
  chart::text(cr, left, 28, style.title, 20, Align::Start, Align::End, true);
  chart::text(cr, left, 52, style.subtitle + (vmaxData > 0 ? "" : "  (no flow in this map)"), 13);

  // Colour scale, or the legend of a categorical map.
  const double barX = left + mapW + 24, barW = 18, barTop = top + 20, barH = std::min(mapH - 20, 320.0);
  if (!style.classes.empty()) {
    for (size_t i = 0; i < style.classes.size(); ++i) {
      const double y = barTop + 26.0 * double(i);
      const chart::Rgb col = style.classes[i].second;
      cairo_set_source_rgb(cr, col.r, col.g, col.b);
      cairo_rectangle(cr, barX, y, barW, barW);
      cairo_fill(cr);
      cairo_set_source_rgb(cr, 0, 0, 0);
      cairo_rectangle(cr, barX + 0.5, y + 0.5, barW - 1, barW - 1);
      cairo_stroke(cr);
      chart::text(cr, barX + barW + 6, y + barW / 2, style.classes[i].first, 12, Align::Start, Align::Centre);
    }
  } else {
    for (int i = 0; i < int(barH); ++i) {
      const chart::Rgb col = chart::ramp(style.ramp, 1 - (i + 0.5) / barH);
      cairo_set_source_rgb(cr, col.r, col.g, col.b);
      cairo_rectangle(cr, barX, barTop + i, barW, 1);
      cairo_fill(cr);
    }
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_rectangle(cr, barX + 0.5, barTop + 0.5, barW - 1, barH - 1);
    cairo_stroke(cr);
    double step = 1;
    for (double t : chart::niceTicks(0, vmax, 5, &step)) {
      const double y = barTop + barH * (1 - t / vmax);
      cairo_move_to(cr, barX + barW, y);
      cairo_line_to(cr, barX + barW + 5, y);
      cairo_stroke(cr);
      chart::text(cr, barX + barW + 8, y, chart::tickLabel(t, step), 12, Align::Start, Align::Centre);
    }
    chart::text(cr, barX, barTop - 8, style.unit, 13, Align::Start, Align::End, true);
  }

  // Scale bar: a nice length near a quarter of the map width, in two halves.
  const double widthM = grid.nx * grid.cellSize;
  double len = std::pow(10.0, std::floor(std::log10(widthM / 4)));
  for (double m : {5.0, 2.0, 1.0})
    if (m * len <= widthM / 4) {
      len *= m;
      break;
    }
  const double pxPerM = mapW / widthM, sbX = left, sbY = top + mapH + 22, sbW = len * pxPerM;
  for (int i = 0; i < 2; ++i) {
    cairo_rectangle(cr, sbX + i * sbW / 2, sbY, sbW / 2, 7);
    if (i == 0) cairo_fill_preserve(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_stroke(cr);
  }
  chart::text(cr, sbX, sbY + 12, "0", 12, Align::Centre, Align::Start);
  chart::text(cr, sbX + sbW, sbY + 12, lengthLabel(len), 12, Align::Centre, Align::Start);
  char cell[64];
  std::snprintf(cell, sizeof cell, "cell %g m", grid.cellSize);
  chart::text(cr, left + mapW, sbY + 12, cell, 11, Align::End, Align::Start);

  // North arrow (the raster is north-up).
  const double nx = left + mapW - 22, ny = top + 14;
  if (style.northUp) {
    cairo_set_source_rgba(cr, 1, 1, 1, 0.8);
    cairo_arc(cr, nx, ny + 16, 15, 0, 2 * M_PI);
    cairo_fill(cr);
    cairo_set_source_rgb(cr, 0, 0, 0);
    cairo_move_to(cr, nx, ny + 4);
    cairo_line_to(cr, nx + 6, ny + 24);
    cairo_line_to(cr, nx, ny + 19);
    cairo_line_to(cr, nx - 6, ny + 24);
    cairo_close_path(cr);
    cairo_fill(cr);
    chart::text(cr, nx, ny + 2, "N", 11, Align::Centre, Align::End, true);
  }

  cairo_destroy(cr);
  cairo_surface_destroy(img);
  return page;
}

void writeMapQuicklook(const std::string& path, const RasterGrid& grid, const std::vector<float>& values,
                       const std::vector<float>& heights, const QuicklookStyle& style, float nodata) {
  cairo_surface_t* page = drawPage(grid, values, hillshade(grid, heights), style, nodata);
  try {
    chart::writePng(page, path);
  } catch (...) {
    cairo_surface_destroy(page);
    throw;
  }
  cairo_surface_destroy(page);
}

MapImage::MapImage(cairo_surface_t* page)
    : page_(page, &cairo_surface_destroy), width_(cairo_image_surface_get_width(page)),
      height_(cairo_image_surface_get_height(page)) {
  // ARGB32 rows are whole words, so cairo pads none (its stride alignment is 4 bytes).
  if (cairo_image_surface_get_stride(page) != 4 * width_) throw std::logic_error("MapImage: padded rows");
  pixels_ = reinterpret_cast<const uint32_t*>(cairo_image_surface_get_data(page));
}

MapImage drawMapQuicklook(const RasterGrid& grid, const std::vector<float>& values, const std::vector<float>& heights,
                          const QuicklookStyle& style, float nodata) {
  return drawMapQuicklook(grid, values, ShadedRelief{hillshade(grid, heights)}, style, nodata);
}

MapImage drawMapQuicklook(const RasterGrid& grid, const std::vector<float>& values, const ShadedRelief& relief,
                          const QuicklookStyle& style, float nodata) {
  cairo_surface_t* page = drawPage(grid, values, relief.shade, style, nodata);
  cairo_surface_flush(page);
  return MapImage(page);
}

} // namespace talus
