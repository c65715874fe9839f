#include "tools/animate_command.h"

#include <CLI/CLI.hpp>
#include <cstdio>
#include <filesystem>

namespace talus {

CLI::App* addAnimateCommand(CLI::App& app, AnimateOptions& o) {
  auto* c = app.add_subcommand("animate", "Draw and encode a run's film again (animation.mp4, animation.gif) from its "
                                          "frame rasters, with another quantity, colour range, frame rate, size or view");
  c->add_option("run_dir", o.dir, "Output folder of a run with [output] animation")->required();
  c->add_option("--quantity", o.style.quantity, "thickness or speed")->check(CLI::IsMember({"thickness", "speed"}));
  c->add_option("--max", o.style.scaleMax, "Top of the colour scale (m or m/s); default: the film's largest value")
      ->check(CLI::PositiveNumber);
  c->add_option("--fps", o.style.fps, "Frames per second")->check(CLI::Range(1, 120));
  c->add_option("--width", o.style.width, "Width of the MP4 in pixels")->check(CLI::Range(64, 7680));
  c->add_option("--gif-width", o.style.gifWidth, "Width of the GIF in pixels")->check(CLI::Range(64, 3840));
  c->add_option("--window", o.window, "World XMIN YMIN XMAX YMAX to show")->expected(4);
  return c;
}

int runAnimateCommand(const AnimateOptions& o) {
  AnimateOptions a = o;
  if (!a.window.empty()) a.style.window = std::array<double, 4>{a.window[0], a.window[1], a.window[2], a.window[3]};
  const AnimationResult r = makeAnimation(a.dir, a.style);
  if (!r.problem.empty()) {
    std::fprintf(stderr, "talus: error: %s\n", r.problem.c_str());
    return 1;
  }
  if (!r.retried.empty())
    std::fprintf(stderr, "talus animate: ffmpeg failed making %s; encoded again alone\n", r.retried.c_str());
  for (const auto& f : r.files)
    std::fprintf(stderr, "talus animate: %d frames of %s -> %s\n", r.frames, a.style.quantity.c_str(),
                 (std::filesystem::path(a.dir) / f).c_str());
  return 0;
}

} // namespace talus
