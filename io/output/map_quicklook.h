// PNG quick-looks of hazard maps: the value in colour over a hillshade of the DEM (or a flat
// background), with title, colour scale and unit, scale bar and north arrow. For a first look
// without GIS; the GeoTIFFs are the data.
#pragma once

#include "io/common/chart_drawing.h"
#include "io/common/raster_grid.h"

#include <cstdint>
#include <memory>
#include <string>
#include <utility>
#include <vector>

namespace talus {

struct QuicklookStyle {
  std::string title;    ///< e.g. "Maximum flow height (vertical)"
  std::string subtitle; ///< e.g. "all materials, t = 0 - 12 s"
  std::string unit;     ///< shown on the colour scale
  chart::Ramp ramp = chart::Ramp::Viridis;
  /// Categorical map instead: value k (1..n) is drawn in classes[k - 1].second, with a legend of
  /// the labels in place of the colour scale (0 shows the background only).
  std::vector<std::pair<std::string, chart::Rgb>> classes;
  double scaleMax = 0;  ///< top of the colour scale; 0 = a round value above the data's maximum
  bool northUp = true;  ///< false for grids that are not north-up maps (AIMEC's (s, l)): no north arrow
};

/// `values` and `heights` (optional, may be empty) cover `grid` row by row (row 0 north).
/// Cells with values <= 0, NaN or equal to `nodata` show the background only. Rasters larger
/// than about 900 px are reduced by taking the maximum of each block of cells, so peaks survive.
void writeMapQuicklook(const std::string& path, const RasterGrid& grid, const std::vector<float>& values,
                       const std::vector<float>& heights, const QuicklookStyle& style, float nodata = -9999);

/// The same picture in memory: width x height pixels, row by row without padding, each a
/// native-endian 0xAARRGGBB word (cairo's ARGB32; opaque), i.e. bytes B, G, R, A on x86. The
/// pixels are the drawing's own (no copy: a film draws hundreds of them).
class MapImage {
public:
  MapImage() = default;
  explicit MapImage(cairo_surface_t* page); ///< takes the surface (ARGB32, flushed)
  int width() const { return width_; }
  int height() const { return height_; }
  const uint32_t* pixels() const { return pixels_; }
  size_t bytes() const { return size_t(width_) * size_t(height_) * sizeof(uint32_t); }

private:
  std::shared_ptr<cairo_surface_t> page_;
  const uint32_t* pixels_ = nullptr;
  int width_ = 0, height_ = 0;
};
MapImage drawMapQuicklook(const RasterGrid& grid, const std::vector<float>& values, const std::vector<float>& heights,
                          const QuicklookStyle& style, float nodata = -9999);

/// The relief under many pictures of one grid (a film's frames), shaded once.
struct ShadedRelief {
  std::vector<float> shade; ///< hillshade(grid, heights), one value per cell of the grid; empty: no relief
};
/// As above, over a relief already shaded for `grid`.
MapImage drawMapQuicklook(const RasterGrid& grid, const std::vector<float>& values, const ShadedRelief& relief,
                          const QuicklookStyle& style, float nodata = -9999);

/// Hillshade in [0, 1] (sun from the north-west, 45 degrees up) of `heights` on `grid`; NaN
/// where the height or all its neighbours are missing.
std::vector<float> hillshade(const RasterGrid& grid, const std::vector<float>& heights);

} // namespace talus
