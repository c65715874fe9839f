// 3D renders of a run through Blender (`talus render RUN_DIR`): the terrain as a shaded mesh
// from maps/ground_elevation.tif, the VDB volume frames (frames/volume_NNNNN.vdb) coloured by
// material, a camera framing the flow's extent over the frames (or one given), a sun and a sky.
// Blender (Debian's `blender`, 3.4) runs headless with a script compiled into Talus
// (io/output/render_blender.py); FFmpeg encodes the PNG frames to an MP4.
#pragma once

#include "engine/types.h"

#include <functional>
#include <optional>
#include <string>
#include <vector>

namespace talus {

struct RenderOptions {
  std::string dir;                   ///< a run's output folder
  int width = 960, height = 540;     ///< pixels
  int samples = 16;                  ///< Cycles samples per pixel
  int fps = 8;                       ///< of render.mp4
  int frame = -1;                    ///< render only this volume frame (index), or all (-1)
  int every = 1;                     ///< every n-th frame
  std::optional<Vec3d> camera, target; ///< world coordinates; default: framing the flow
  std::string blender;               ///< the program; default: `blender` on the PATH
};

struct RenderResult {
  std::vector<std::string> files; ///< relative to the run folder: render/frame_*.png, render/render.mp4
  int frames = 0;
  /// Empty when the pictures were made; else why not (Blender missing or failing), in one line.
  std::string problem;
};

/// Renders the run in `o.dir` into o.dir/render/. `progress(done, total)` is called after each
/// frame. Throws InputError (naming the folder or option) when the folder has no volume frames,
/// a frame cannot be read, or the options select none.
RenderResult makeRender(const RenderOptions& o, const std::function<void(int, int)>& progress = {});

/// The Blender script (io/output/render_blender.py, compiled in).
const std::string& renderBlenderScript();

} // namespace talus
