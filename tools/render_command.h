// `talus render RUN_DIR`: 3D renders of a run's volume frames over its terrain, through Blender.
#pragma once

#include "io/output/render.h"

namespace CLI {
class App;
}

namespace talus {

struct RenderCommandOptions {
  RenderOptions render;
  std::vector<double> camera, target; ///< world x y z, or empty
};

CLI::App* addRenderCommand(CLI::App& app, RenderCommandOptions& o);
/// Prints the pictures written (or why not) and returns the exit status; throws InputError.
int runRenderCommand(const RenderCommandOptions& o);

} // namespace talus
