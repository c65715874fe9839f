#include "io/run_driver.h"

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

namespace {
std::string framePath(const std::string& dir, int frame) {
  char name[64];
  std::snprintf(name, sizeof name, "particles_%05d.h5", frame);
  return (std::filesystem::path(dir) / "frames" / name).string();
}
} // namespace

RunResult runScene(SceneSetup& scene, const RunOptions& opt) {
  RunResult res;
  res.outDir = opt.outDir.empty() ? scene.output.directory : opt.outDir;
  std::filesystem::create_directories(res.outDir);
  const int threads = opt.threads > 0 ? opt.threads : int(tbb::info::default_concurrency());
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));

  Simulation sim(scene.settings, std::move(scene.groups));
  const double interval = scene.output.frameInterval;
  if (interval > 0) std::filesystem::create_directories(std::filesystem::path(res.outDir) / "frames");
  int frame = 0;
  if (interval > 0) writeParticlesH5(framePath(res.outDir, frame++), sim, scene.materialNames);

  ProgressBar bar(scene.endTime, stderr, opt.progress);
  const auto t0 = std::chrono::steady_clock::now();
  RunInfo info;
  info.scene = scene.file;
  info.threads = threads;
  info.materialNames = scene.materialNames;
  try {
    while (sim.time() < scene.endTime) {
      const double next = interval > 0 ? std::min(scene.endTime, frame * interval) : scene.endTime;
      sim.advanceTo(next, [&] { bar.update(sim.time(), sim.steps(), sim.particleSteps()); });
      if (interval > 0 && next == frame * interval)
        writeParticlesH5(framePath(res.outDir, frame++), sim, scene.materialNames);
    }
  } catch (const NumericalError& e) {
    res.ok = false;
    res.error = e.what();
    info.status = std::string("failed: ") + e.what();
  }
  bar.finish();
  res.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  info.wallSeconds = res.wallSeconds;
  if (res.ok) writeParticlesH5((std::filesystem::path(res.outDir) / "particles.h5").string(), sim, scene.materialNames);
  writeSummaryJson((std::filesystem::path(res.outDir) / "summary.json").string(), sim, info);
  return res;
}

} // namespace talus
