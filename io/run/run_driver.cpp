#include "io/run/run_driver.h"

#include "io/common/write_error.h"
#include "io/run/checkpoint.h"
#include "io/output/output_set.h"
#include "io/output/particle_writer.h"
#include "io/run/progress_bar.h"
#include "io/run/run_ranks.h"
#include "io/run/run_signals.h"
#include "io/run/run_summary.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <filesystem>
#include <optional>
#include <tbb/global_control.h>
#include <tbb/info.h>

namespace talus {

namespace {
/// Thrown from the step callback to leave the time loop after a stop signal.
struct StopRequested {
  int signal;
};

/// Creating a folder fails like writing a file (full, read-only, removed): report it as one.
void makeDirectories(const std::string& dir) {
  std::error_code ec;
  std::filesystem::create_directories(dir, ec);
  if (ec) throw WriteError(dir, ec.message());
}
} // namespace

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
  RunRanks ranks(opt.ranks);
  res.outDir = opt.outDir.empty() ? scene.output.directory : opt.outDir;
  const int threads = opt.threads > 0 ? opt.threads : int(tbb::info::default_concurrency());
  tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));

  Simulation sim(scene.settings, std::move(scene.groups));
  // With ranks, rank 0 writes every output from a view of the whole run (Simulation::gatherInto).
  std::unique_ptr<Simulation> viewed;
  if (ranks.active() && ranks.root()) {
    SceneSetup again = opt.viewScene();
    viewed = std::make_unique<Simulation>(again.settings, std::move(again.groups));
  }
  Simulation& view = viewed ? *viewed : sim;
  // Whole particles for frames, checkpoints and the end; positions, velocities and masses (all
  // the per-step outputs read) after every other step.
  auto gather = [&](Simulation::GatherScope scope) {
    if (ranks.active()) sim.gatherInto(viewed.get(), scope);
  };
  auto gatherWhole = [&] { gather(Simulation::GatherScope::Whole); };
  RunInfo info;
  info.scene = scene.file;
  info.threads = threads;
  info.materialNames = scene.materialNames;
  info.notes = scene.notes;
  std::optional<OutputSet> outputs;
  const auto t0 = std::chrono::steady_clock::now();
  auto record = [&] {
    res.steps = sim.steps(), res.time = sim.time();
    res.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    info.wallSeconds = res.wallSeconds;
    if (outputs) info.outputs = outputs->reports();
    res.files.clear();
    for (const auto& o : info.outputs) res.files.insert(res.files.end(), o.files.begin(), o.files.end());
    res.files.push_back("summary.json");
  };
  const std::string summaryFile = (fs::path(res.outDir) / "summary.json").string();
  const std::string checkpointFile = checkpointPath(res.outDir);
  const CheckpointIdentity identity{scene.hash, scene.stateKeys};

  auto writeFailed = [&](const WriteError& e) {
    res.status = RunStatus::WriteFailure;
    res.error = e.what();
    info.status = std::string("failed: ") + e.what();
    record();
    try {
      writeSummaryJson(summaryFile, view, info);
    } catch (const WriteError&) {
      // The disk refuses it as well; the error above is the one to report.
    }
  };

  // Outputs always start from the initial state (maps keep its thicknesses for erosion); a
  // resumed run then replaces their accumulated state with the checkpoint's. A refused
  // checkpoint throws InputError before anything is written.
  int frame = 0;
  const double interval = scene.output.frameInterval;
  const double checkpointEvery =
      scene.output.checkpointInterval < 0 ? scene.endTime / 10 : scene.output.checkpointInterval;
  double nextCheckpoint = checkpointEvery > 0 ? checkpointEvery : std::numeric_limits<double>::infinity();
  std::optional<RunSignals> signals;
  if (opt.handleSignals) signals.emplace(opt.progress);
  try {
    ranks.onRoot([&] {
      makeDirectories(res.outDir);
      outputs.emplace(scene.output, scene.runContext(), res.outDir); // only what [output] asks for
      outputs->start(view);
    });
    if (opt.resume) {
      // Every rank reads the whole checkpoint (one process's arrays), then keeps its own blocks:
      // a run checkpointed at N ranks resumes at any M.
      readCheckpoint(checkpointFile, sim, identity, [&](const StateArchive& a) {
        if (outputs) outputs->load(a);
        frame = a.getValue<int32_t>("driver/next_frame");
        nextCheckpoint = a.getValue<double>("driver/next_checkpoint");
        // A resumed run may have another frame interval: its frames continue after this time.
        if (a.getValue<double>("driver/frame_interval") != interval)
          frame = interval > 0 ? int(std::floor(sim.time() / interval + 1e-9)) + 1 : 0;
      });
      res.checkpointTime = sim.time();
    }
    // The first frame before distributing: binning reorders the particles, and one process
    // writes this frame in seeding order.
    if (!opt.resume && interval > 0) {
      ranks.onRoot([&] { outputs->frame(view, frame); });
      ++frame;
    }
    if (ranks.active()) {
      // Each rank seeded its part (unless resumed: then every rank read every particle).
      const bool seededInParts = scene.seedSlice.active() && !opt.resume;
      sim.distribute(opt.ranks, 0.1, seededInParts ? &scene.seedSlice.index : nullptr);
      gatherWhole();
    }
    auto checkpoint = [&] {
      gatherWhole();
      ranks.onRoot([&] {
        writeCheckpoint(checkpointFile, view, identity, [&](StateArchive& a) {
          outputs->save(a);
          a.putValue("driver/next_frame", int32_t(frame));
          a.putValue("driver/frame_interval", interval);
          a.putValue("driver/next_checkpoint", nextCheckpoint);
        });
      });
      res.checkpointTime = sim.time();
    };

    RootLoadBalance balance;
    ProgressBar bar(scene.endTime, stderr, opt.progress && ranks.root());
    try {
      while (sim.time() < scene.endTime) {
        const double frameTime = frame * interval;
        const double next = interval > 0 ? std::min(scene.endTime, frameTime) : scene.endTime;
        sim.advanceTo(next, [&] {
          if (scene.output.readsEveryStep()) {
            gather(Simulation::GatherScope::Kinematics);
            ranks.onRoot([&] {
              // Not the gather: its time includes waiting for slower ranks.
              const auto o0 = std::chrono::steady_clock::now();
              outputs->step(view);
              balance.addOutputSeconds(std::chrono::duration<double>(std::chrono::steady_clock::now() - o0).count());
            });
          }
          if (ranks.active()) balance.afterStep(ranks, sim);
          bar.update(sim.time(), sim.steps(), sim.particleSteps());
          if (ranks.active() && ranks.root() && opt.handleSignals) {
            char line[200];
            std::snprintf(line, sizeof line, "talus: the job was at step %llu (t = %.6g s); its last checkpoint (t = %.6g s) is whole; mpirun names a rank that failed",
                          (unsigned long long)sim.steps(), sim.time(), res.checkpointTime);
            setStopContext(line);
          }
          // Signals are read once per step, after the step, when the state is whole (under MPI,
          // the ranks' flags are reduced here). SIGUSR1: the job may be killed soon.
          const bool asked = ranks.agree(takeCheckpointRequest());
          if (sim.time() >= nextCheckpoint && sim.time() < scene.endTime) {
            nextCheckpoint += checkpointEvery;
            checkpoint(); // the last good state: a failure later never overwrites it
          } else if (asked) {
            checkpoint();
          }
          // At the end time the run is complete: its final outputs are quicker than a resume.
          if (const int s = ranks.agree(stopSignalReceived()); s && sim.time() < scene.endTime) throw StopRequested{s};
        });
        // 3 * 0.1 > 0.3 in floating point: the last frame is due when the end time is within
        // rounding of it.
        if (interval > 0 && next >= frameTime - 1e-9 * interval) {
          gatherWhole();
          ranks.onRoot([&] { outputs->frame(view, frame); });
          ++frame;
        }
      }
    } catch (const NumericalError& e) {
      res.status = RunStatus::NumericalFailure;
      res.error = e.what();
      info.status = std::string("failed: ") + e.what();
    } catch (const StopRequested& s) {
      res.status = RunStatus::Interrupted;
      res.signal = s.signal;
      info.status = "interrupted";
      info.signal = signalName(s.signal);
      checkpoint();
    }
    bar.finish();
    if (res.status != RunStatus::Interrupted) gatherWhole();
    if (res.status != RunStatus::Interrupted)
      ranks.onRoot([&] {
        outputs->finish(view, res.status == RunStatus::Completed);
        if (res.status == RunStatus::Completed)
          writeParticlesH5((fs::path(res.outDir) / "particles.h5").string(), view, scene.materialNames);
      });
    if (ranks.active()) info.ranks = rankFigures(sim);
    record();
    ranks.onRoot([&] { writeSummaryJson(summaryFile, view, info); });
  } catch (const WriteError& e) {
    writeFailed(e);
  } catch (const fs::filesystem_error& e) { // a folder an output creates
    writeFailed(WriteError(e.path1().string(), e.code().message()));
  } catch (const PeerFailed&) {
    record(); // rank 0 failed and reports it; its status is agreed below
  }
  if (ranks.active()) res.status = RunStatus(ranks.agree(ranks.root() ? int(res.status) : 0));
  res.ok = res.status == RunStatus::Completed;
  return res;
}

} // namespace talus
