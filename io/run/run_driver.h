// `talus run`: a scene from start to end time, writing frames, particles.h5 and summary.json.
#pragma once

#include "io/scene/scene.h"

#include <string>
#include <vector>

namespace talus {

struct RunOptions {
  std::string outDir;          ///< overrides [output].directory when not empty
  int threads = 0;             ///< 0 = all hardware threads
  bool progress = true;        ///< progress bar when stderr is a terminal
  bool resume = false;         ///< continue from outDir/checkpoint.h5 instead of starting anew
};

struct RunResult {
  std::string outDir;
  double wallSeconds = 0;
  bool ok = true;
  std::string error;
  std::vector<std::string> files; ///< everything the outputs wrote, relative to outDir
};

/// What a user should look at after a run, most telling first: a hazard map quick-look when
/// there are maps, else a plot, else summary.json (relative to the output directory).
std::vector<std::string> filesToOpenFirst(const RunResult& r);

/// Runs a built scene to its end time; the scene's material groups move into the simulation, so
/// the caller hands the scene over (std::move). Numerical failures are reported in the result
/// (and in summary.json) instead of thrown; outputs already written stay in place.
RunResult runScene(SceneSetup&& scene, const RunOptions& options);

} // namespace talus
