#include "io/run/run_driver.h"

#include "io/run/checkpoint.h"
#include "io/output/output_set.h"
#include "io/output/particle_writer.h"
#include "io/run/progress_bar.h"
#include "io/run/run_summary.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <filesystem>
#include <tbb/global_control.h>
#include <tbb/info.h>

namespace talus {

std::vector<std::string> filesToOpenFirst(const RunResult& r) {
  std::vector<std::string> out;
  for (const char* f : {"maps/max_flow_height_vertical.png", "maps/max_speed.png", "maps/max_pressure.png",
                        "plots/kinetic_energy.png", "series.csv", "summary.json"})
    if (std::find(r.files.begin(), r.files.end(), f) != r.files.end()) out.push_back(f);
  return out;
}

RunResult runScene(SceneSetup&& scene, const RunOptions& opt) {
  namespace fs = std::filesystem;
  RunResult res;
  res.outDir = opt.outDir.empty() ? scene.output.directory : opt.outDir;
  fs::create_directories(res.outDir);
  const int threads = opt.threads > 0 ? opt.threads : int(tbb::info::default_concurrency());
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));

  Simulation sim(scene.settings, std::move(scene.groups));
  OutputSet outputs(scene.output, scene.runContext(), res.outDir); // only what [output] asks for
  const double interval = scene.output.frameInterval;
  const double checkpointEvery =
      scene.output.checkpointInterval < 0 ? scene.endTime / 10 : scene.output.checkpointInterval;
  const std::string checkpointFile = checkpointPath(res.outDir);
  const CheckpointIdentity identity{scene.hash};
  int frame = 0;
  double nextCheckpoint = checkpointEvery > 0 ? checkpointEvery : std::numeric_limits<double>::infinity();
  // Outputs always start from the initial state (maps keep its thicknesses for erosion); a
  // resumed run then replaces their accumulated state with the checkpoint's.
  outputs.start(sim);
  if (opt.resume) {
    readCheckpoint(checkpointFile, sim, identity, [&](const StateArchive& a) {
      outputs.load(a);
      frame = a.getValue<int32_t>("driver/next_frame");
      nextCheckpoint = a.getValue<double>("driver/next_checkpoint");
    });
  } else if (interval > 0) {
    outputs.frame(sim, frame++);
  }
  auto checkpoint = [&] {
    writeCheckpoint(checkpointFile, sim, identity, [&](StateArchive& a) {
      outputs.save(a);
      a.putValue("driver/next_frame", int32_t(frame));
      a.putValue("driver/next_checkpoint", nextCheckpoint);
    });
  };

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
        if (sim.time() >= nextCheckpoint && sim.time() < scene.endTime) {
          nextCheckpoint += checkpointEvery;
          checkpoint(); // the last good state: a failure later never overwrites it
        }
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
  for (const auto& o : info.outputs) res.files.insert(res.files.end(), o.files.begin(), o.files.end());
  res.files.push_back("summary.json");
  if (res.ok) writeParticlesH5((fs::path(res.outDir) / "particles.h5").string(), sim, scene.materialNames);
  writeSummaryJson((fs::path(res.outDir) / "summary.json").string(), sim, info);
  return res;
}

} // namespace talus
