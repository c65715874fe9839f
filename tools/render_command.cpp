#include "tools/render_command.h"

#include <CLI/CLI.hpp>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <unistd.h>

namespace talus {

CLI::App* addRenderCommand(CLI::App& app, RenderCommandOptions& o) {
  auto* c = app.add_subcommand("render", "Render a run's volume frames over its terrain in 3D with Blender "
                                         "(render/frame_*.png, render/render.mp4)");
  RenderOptions& r = o.render;
  c->add_option("run_dir", r.dir, "Output folder of a run with volume frames (frames/volume_*.vdb)")->required();
  c->add_option("--width", r.width, "Width in pixels (default 960)")->check(CLI::Range(16, 7680));
  c->add_option("--height", r.height, "Height in pixels (default 540)")->check(CLI::Range(16, 4320));
  c->add_option("--samples", r.samples, "Cycles samples per pixel (default 16)")->check(CLI::Range(1, 4096));
  c->add_option("--frame", r.frame, "Render only this volume frame (index from 0)")->check(CLI::NonNegativeNumber);
  c->add_option("--every", r.every, "Render every n-th frame (default 1)")->check(CLI::Range(1, 100000));
  c->add_option("--fps", r.fps, "Frames per second of render.mp4 (default 8)")->check(CLI::Range(1, 120));
  c->add_option("--camera", o.camera, "Camera position, world X Y Z (default: framing the flow from the south)")->expected(3);
  c->add_option("--target", o.target, "Point the camera looks at, world X Y Z (default: the flow's centre)")->expected(3);
  c->add_option("--blender", r.blender, "The Blender program (default: blender on the PATH)");
  return c;
}

int runRenderCommand(const RenderCommandOptions& o) {
  RenderOptions r = o.render;
  if (!o.camera.empty()) r.camera = Vec3d(o.camera[0], o.camera[1], o.camera[2]);
  if (!o.target.empty()) r.target = Vec3d(o.target[0], o.target[1], o.target[2]);
  // Progress with ETA on a terminal, as `talus run` shows it.
  const bool tty = isatty(fileno(stderr));
  const auto t0 = std::chrono::steady_clock::now();
  auto progress = [&](int done, int total) {
    if (!tty) return;
    const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    std::fprintf(stderr, "\rtalus render: frame %d/%d, %.0f s, ETA %.0f s   ", done, total, s, s / done * (total - done));
    if (done == total) std::fprintf(stderr, "\n");
  };
  const RenderResult res = makeRender(r, progress);
  if (!res.problem.empty() && res.frames == 0) {
    std::fprintf(stderr, "talus: error: %s\n", res.problem.c_str());
    return 1;
  }
  for (const auto& f : res.files) std::fprintf(stderr, "talus render: %s\n", (std::filesystem::path(r.dir) / f).c_str());
  if (!res.problem.empty()) std::fprintf(stderr, "talus render: warning: %s\n", res.problem.c_str());
  return 0;
}

} // namespace talus
