// The run as a film: per-frame rasters of flow thickness and speed, recorded by the hazard maps
// while the run goes (animation/rasters/<quantity>_NNNNN.tif, GeoTIFFs on the maps' grid), then
// drawn with the quick-looks' look (hillshade, colour scale with a range fixed over the film,
// scale bar, north arrow, the time) and encoded with FFmpeg as animation.mp4 (H.264) and
// animation.gif (smaller, for a page). `talus animate RUN_DIR` draws and encodes them again with
// other choices; the rasters are the data, the films are made from them alone.
#pragma once

#include "io/common/raster_grid.h"

#include <array>
#include <optional>
#include <string>
#include <vector>

namespace talus {

/// The quantities a frame records, in file-name order.
inline const std::array<const char*, 2>& animationQuantities() {
  static const std::array<const char*, 2> q{"thickness", "speed"};
  return q;
}

/// Writes frame `index` at `time` (s): one GeoTIFF per quantity (values on `grid`, 0 where there
/// is no flow, NaN where unknown) into DIR/animation/rasters/. Returns the files written (relative to
/// DIR). Throws WriteError.
std::vector<std::string> writeAnimationFrame(const std::string& dir, int index, double time, const RasterGrid& grid,
                                             const std::vector<float>& thickness, const std::vector<float>& speed);

struct AnimationStyle {
  std::string quantity = "thickness"; ///< one of animationQuantities()
  double scaleMax = 0;                ///< top of the colour scale; 0 = the film's largest value
  int fps = 10;
  int width = 0;                      ///< MP4 width in pixels (even); 0 = the drawing's (~1000)
  int gifWidth = 480;
  /// World xmin, ymin, xmax, ymax to show; empty = the rasters' extent.
  std::optional<std::array<double, 4>> window;
  /// What the run that wrote the frames knows of them: how many it wrote (from 0) and the largest
  /// value of each quantity (animationQuantities' order). Used for the colour scale instead of
  /// reading every frame first, when the folder holds exactly that many and no window is set.
  struct Known {
    size_t frames = 0;
    std::array<float, 2> largest{};
  };
  std::optional<Known> known;
};

struct AnimationResult {
  std::vector<std::string> files; ///< relative to the run folder
  int frames = 0;
  /// Empty when the films were made; else why not (FFmpeg missing or failing), in one line.
  std::string problem;
  /// The films encoded a second time, alone, after their first encoder failed, with ffmpeg's
  /// first message ("" for none).
  std::string retried;
};

/// Draws DIR/animation/rasters/<quantity>_*.tif over the hillshade of DIR/maps/ground_elevation.tif
/// (when there) and encodes DIR/animation.mp4 and DIR/animation.gif with the `ffmpeg` program.
/// Without ffmpeg on the PATH (or when it fails) the drawn frames stay in DIR/animation/png/ and
/// `problem` says so. Throws InputError when the folder holds no frames of that quantity or the
/// style is invalid, WriteError when a file cannot be written.
AnimationResult makeAnimation(const std::string& dir, const AnimationStyle& style);

} // namespace talus
