#include "io/run_driver.h"

#include "io/output_set.h"
#include "io/particle_writer.h"
#include "io/progress_bar.h"
#include "io/run_summary.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <tbb/global_control.h>
#include <tbb/info.h>

namespace talus {

RunResult runScene(SceneSetup& scene, const RunOptions& opt) {
  namespace fs = std::filesystem;
  RunResult res;
  res.outDir = opt.outDir.empty() ? scene.output.directory : opt.outDir;
  fs::create_directories(res.outDir);
  const int threads = opt.threads > 0 ? opt.threads : int(tbb::info::default_concurrency());
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));

  Simulation sim(scene.settings, std::move(scene.groups));
  OutputSet outputs(scene, res.outDir); // only what [output] asks for
  const double interval = scene.output.frameInterval;
  int frame = 0;
  outputs.start(sim);
  if (interval > 0) outputs.frame(sim, frame++);

  ProgressBar bar(scene.endTime, stderr, opt.progress);
  const auto t0 = std::chrono::steady_clock::now();
  RunInfo info;
  info.scene = scene.file;
  info.threads = threads;
  info.materialNames = scene.materialNames;
  try {
    while (sim.time() < scene.endTime) {
      const double frameTime = frame * interval;
      const double next = interval > 0 ? std::min(scene.endTime, frameTime) : scene.endTime;
      sim.advanceTo(next, [&] {
        outputs.step(sim);
        bar.update(sim.time(), sim.steps(), sim.particleSteps());
      });
      // 3 * 0.1 > 0.3 in floating point: the last frame is due when the end time is within
      // rounding of it.
      if (interval > 0 && next >= frameTime - 1e-9 * interval) outputs.frame(sim, frame++);
    }
  } catch (const NumericalError& e) {
    res.ok = false;
    res.error = e.what();
    info.status = std::string("failed: ") + e.what();
  }
  bar.finish();
  outputs.finish(sim, res.ok);
  res.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  info.wallSeconds = res.wallSeconds;
  info.outputs = outputs.reports();
  if (res.ok) writeParticlesH5((fs::path(res.outDir) / "particles.h5").string(), sim, scene.materialNames);
  writeSummaryJson((fs::path(res.outDir) / "summary.json").string(), sim, info);
  return res;
}

} // namespace talus
