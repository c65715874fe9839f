#include "io/run/run.h"

#include "io/common/write_error.h"
#include "io/output/output_set.h"
#include "io/output/particle_writer.h"
#include "io/output/report_page.h"
#include "io/run/checkpoint.h"
#include "io/run/checkpoint_parts.h"
#include "io/run/progress_bar.h"
#include "io/run/run_ranks.h"
#include "io/run/run_state.h"
#include "io/run/run_signals.h"
#include "io/run/run_summary.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <malloc.h>
#include <optional>
#include <tbb/global_control.h>
#include <tbb/info.h>
#include <tbb/task_arena.h>

namespace talus {

namespace fs = std::filesystem;

namespace {
/// Creating a folder fails like writing a file (full, read-only, removed): report it as one.
void makeDirectories(const std::string& dir) {
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw WriteError(dir, ec.message());
}
} // namespace


Run::Run(SceneSetup&& scene, const RunOptions& opt) : s_(std::make_unique<State>(scene, opt)) {
  State& s = *s_;
  res_.outDir = opt.outDir.empty() ? scene.output.directory : opt.outDir;
  endTime_ = scene.endTime;
  s.threads = opt.threads > 0 ? opt.threads : int(tbb::info::default_concurrency());
  s.threadLimit = std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(s.threads));
  sim_ = std::make_unique<Simulation>(scene.settings, std::move(scene.groups));
  // With ranks, rank 0 writes every output from a view of the whole run (Simulation::gatherInto).
  if (s.ranks.active() && s.ranks.root()) {
    // The view's arrays are freed after every write (State::releaseView). glibc raises its mmap
    // threshold to the size of a freed block (up to 32 MB), so later blocks of that size, the
    // steps' own buffers among them, come from its heap instead: rank 0's steps took 8 % longer
    // (docs/scaling.md, "Rank 0's view"). A threshold set once is not moved, and the view's
    // arrays stay mapped apart, returned whole when freed.
    mallopt(M_MMAP_THRESHOLD, 128 * 1024); // glibc's default
    s.viewed = sim_->emptyView(); // filled from the ranks' parts below, not seeded again
  }
  s.view = s.viewed ? s.viewed.get() : sim_.get();
  s.info.scene = scene.file;
  s.info.threads = s.threads;
  s.info.materialNames = scene.materialNames;
  s.info.notes = scene.notes;
  s.summaryFile = (fs::path(res_.outDir) / "summary.json").string();
  s.checkpointFile = checkpointPath(res_.outDir);
  if (s.checkpointEvery > 0) s.nextCheckpoint = s.checkpointEvery;
  if (opt.handleSignals) s.signals.emplace(opt.progress);
  // Outputs always start from the initial state (maps keep its thicknesses for erosion); a
  // resumed run then replaces their accumulated state with the checkpoint's. A refused
  // checkpoint throws InputError before anything is written.
  // Each rank seeded its part (unless resumed: then every rank read every particle).
  const bool seededInParts = scene.seedSlice.active() && !opt.resume;
  guarded([&] {
    startOutputs(scene, seededInParts);
    if (opt.resume) resume();
    // The first frame before distributing: binning reorders the particles, and one process
    // writes this frame in seeding order.
    if (!opt.resume && s.interval > 0) {
      s.ranks.onRoot([&] { s.outputs->frame(*s.view, s.frame); });
      ++s.frame;
    }
    if (s.ranks.active()) {
      sim_->distribute(opt.ranks, 0.1, seededInParts ? &scene.seedSlice.index : nullptr);
      s.releaseView(); // its whole initial state served the outputs' start and frame 0
      shareOutputState();
    }
    s.bar = std::make_unique<ProgressBar>(endTime_, stderr, opt.progress && s.ranks.root());
  });
}

void Run::startOutputs(const SceneSetup& scene, bool seededInParts) {
  State& s = *s_;
  // The outputs' start and frame 0 read every particle as seeded, in one process's order.
  if (s.ranks.active()) {
    sim_->gatherSeededInto(s.ranks.comm(), s.viewed.get(), seededInParts ? &scene.seedSlice.index : nullptr);
    ++s.info.wholeGathers;
  }
  s.ranks.onRoot([&] {
    makeDirectories(res_.outDir);
    s.outputs.emplace(scene.output, scene.runContext(), res_.outDir); // only what [output] asks for
    s.outputs->start(*s.view);
  });
  // Each rank writes its part of a checkpoint or frame where every rank sees the output folder.
  s.writesInParts = s.ranks.active() && s.ranks.shareFolder(res_.outDir);
  if (s.ranks.active() && !s.writesInParts && s.ranks.root()) {
    s.info.notes.push_back(res_.outDir + " is not the same folder on every rank (a node's own disk?): checkpoints "
                           "and frames are written by rank 0 with every particle, not in parts by each rank");
    std::fprintf(stderr, "talus: %s\n", s.info.notes.back().c_str());
  }
  // The other ranks make the parts of the per-step outputs that reduce (OutputSet::parts) and
  // write their parts of the frames.
  if (!s.ranks.root())
    s.outputs.emplace(OutputSet::PartsOnly{}, scene.output, scene.runContext(), *sim_,
                      s.writesInParts ? res_.outDir : std::string());
}

void Run::resume() {
  State& s = *s_;
  // Every rank reads the whole checkpoint (one process's arrays), then keeps its own blocks: a
  // run checkpointed at N ranks resumes at any M.
  readCheckpoint(s.checkpointFile, *sim_, s.identity, [&](const StateArchive& a) {
    if (s.outputs && s.ranks.root()) s.outputs->load(a);
    else if (s.outputs) s.outputs->loadClock(a); // the others' parts keep no state
    s.frame = a.getValue<int32_t>("driver/next_frame");
    s.nextCheckpoint = a.getValue<double>("driver/next_checkpoint");
    // A resumed run may have another frame interval: its frames continue after this time.
    if (a.getValue<double>("driver/frame_interval") != s.interval)
      s.frame = s.interval > 0 ? int(std::floor(sim_->time() / s.interval + 1e-9)) + 1 : 0;
  });
  res_.checkpointTime = sim_->time();
}

Run::~Run() = default;

size_t Run::viewCapacity() const {
  size_t n = 0;
  if (s_->viewed)
    for (const MaterialGroup* g : s_->viewed->groups()) n += g->particles.x.capacity();
  return n;
}

bool Run::step() {
  if (ended_) return false;
  State& s = *s_;
  guarded([&] {
    try {
      if (sim_->time() < endTime_) {
        // Frames fall on multiples of the interval: the steps toward one end exactly on it.
        const double frameTime = s.frame * s.interval;
        const double target = s.interval > 0 ? std::min(endTime_, frameTime) : endTime_;
        // A run resumed at a frame's time writes that frame before it steps again.
        if (sim_->time() < target) {
          sim_->stepToward(target);
          afterStep();
          if (ended_) return; // stopped by a signal
        }
        // 3 * 0.1 > 0.3 in floating point: the frame is due when the target is within rounding
        // of its time.
        if (sim_->time() >= target && s.interval > 0 && target >= frameTime - 1e-9 * s.interval) writeFrame();
      }
    } catch (const NumericalError& e) {
      res_.status = RunStatus::NumericalFailure;
      res_.error = e.what();
      s.info.status = std::string("failed: ") + e.what();
    }
    if (res_.status == RunStatus::NumericalFailure || sim_->time() >= endTime_) finish();
  });
  return !ended_;
}

void Run::writeFrame() {
  State& s = *s_;
  // Each rank writes its rows of the HDF5 and PLY frames and scatters its particles for the VDB
  // volume; rank 0 gathers every particle only for VDB points, or when the ranks do not share
  // the output folder.
  const WriteHeap heap(s.viewed != nullptr); // the VDB volume's node sums, or the view
  std::optional<WriteError> failure;
  if (s.writesInParts) failure = s.outputs->frameParts(s.ranks.comm(), *sim_, s.frame);
  const bool whole = !s.writesInParts || s.output.framesNeedEveryParticle();
  if (whole) s.gatherView(*sim_);
  s.ranks.onRoot([&] {
    if (failure) throw *failure;
    if (whole) s.outputs->frame(*s.view, s.frame, s.writesInParts);
  });
  s.releaseView();
  ++s.frame;
}

bool Run::advanceTo(double t, const std::function<void()>& after) {
  while (!ended_ && sim_->time() < std::min(t, endTime_)) {
    step();
    if (after) after();
  }
  // At the end time the run finishes even when no step was left to take.
  if (!ended_ && sim_->time() >= endTime_) step();
  return !ended_;
}

void Run::afterStep() {
  State& s = *s_;
  // Signals are read once per step, after the step, when the state is whole. SIGUSR1: the job
  // may be killed soon.
  Agreed flags{takeCheckpointRequest(), stopSignalReceived()};
  if (s.ranks.active()) flags = stepOnRanks(flags); // one reduction: the outputs' and the flags
  else if (s.output.readsEveryStep()) s.outputs->step(*sim_);
  if (s.ranks.active()) s.balance.afterStep(s.ranks, *sim_);
  s.bar->update(sim_->time(), sim_->steps(), sim_->particleSteps());
  if (s.ranks.active() && s.ranks.root() && s.opt.handleSignals) {
    char line[200];
    std::snprintf(line, sizeof line, "talus: the job was at step %llu (t = %.6g s); its last checkpoint (t = %.6g s) is whole; mpirun names a rank that failed",
                  (unsigned long long)sim_->steps(), sim_->time(), res_.checkpointTime);
    setStopContext(line);
  }
  if (sim_->time() >= s.nextCheckpoint && sim_->time() < endTime_) {
    s.nextCheckpoint += s.checkpointEvery;
    checkpoint(); // the last good state: a failure later never overwrites it
  } else if (flags.checkpoint) {
    checkpoint();
  }
  // At the end time the run is complete: its final outputs are quicker than a resume.
  if (flags.signal && sim_->time() < endTime_) interrupt(flags.signal);
}

void Run::checkpoint() {
  State& s = *s_;
  guarded([&] {
    // On ranks each writes its particles into a part (io/run/checkpoint_parts.h) and rank 0's
    // view gets the rest of the state only: rank 0 never holds every particle for a checkpoint.
    // (Ranks that do not share the output folder gather every particle to rank 0 instead.)
    WrittenParts parts;
    if (s.writesInParts) {
      sim_->gatherInto(s.viewed.get(), Simulation::ViewContents::WithoutParticles);
      parts = writeCheckpointParts(s.ranks.comm(), s.checkpointFile, *sim_);
    } else {
      s.gatherView(*sim_);
    }
    gatherOutputState();
    s.ranks.onRoot([&] {
      if (parts.failure) throw *parts.failure;
      writeCheckpoint(s.checkpointFile, *s.view, s.identity, [&](StateArchive& a) {
        s.outputs->save(a);
        a.putValue("driver/next_frame", int32_t(s.frame));
        a.putValue("driver/frame_interval", s.interval);
        a.putValue("driver/next_checkpoint", s.nextCheckpoint);
        if (s.writesInParts) {
          const std::string list = partListText(parts.parts);
          a.put(kPartList, list.data(), list.size());
        }
      });
      removeStaleParts(s.checkpointFile, parts.parts); // the parts of the checkpoint replaced
    });
    res_.checkpointTime = sim_->time();
    // Interrupted, the end's summary is written from this view next (finish): every particle.
    if (res_.status != RunStatus::Interrupted) s.releaseView();
    else if (s.writesInParts) s.gatherView(*sim_);
  });
}

void Run::interrupt(int signal) {
  if (ended_) return;
  res_.status = RunStatus::Interrupted;
  res_.signal = signal;
  s_->info.status = "interrupted";
  if (signal) s_->info.signal = signalName(signal);
  checkpoint();
  if (!ended_) guarded([&] { finish(); });
}

void Run::finish() {
  State& s = *s_;
  s.bar->finish();
  const bool interrupted = res_.status == RunStatus::Interrupted;
  if (!interrupted) {
    s.gatherView(*sim_);
    gatherOutputState();
    const WriteHeap heap(s.viewed != nullptr); // the film's pictures, the maps
    // The end's maps and film take seconds on rank 0 while the others would only wait.
    s.ranks.onRootWithNodeCores(s.threads, [&](int cores) {
      s.withThreads(cores, [&] {
        s.outputs->finish(*s.view, res_.status == RunStatus::Completed);
        if (res_.status == RunStatus::Completed)
          writeParticlesH5((fs::path(res_.outDir) / "particles.h5").string(), *s.view, s.materialNames);
      });
    });
  }
  if (s.ranks.active()) s.info.ranks = rankFigures(*sim_);
  else s.info.memory = memoryFigures(*sim_);
  record();
  s.ranks.onRoot([&] {
    const std::string summary = writeSummaryJson(s.summaryFile, *s.view, s.info);
    if (s.output.report) writeReportPage(res_.outDir, summary, res_.files);
  });
  if (s.output.report) res_.files.push_back("report.html");
  ended_ = true;
}

void Run::record() {
  State& s = *s_;
  res_.steps = sim_->steps(), res_.time = sim_->time();
  res_.wallSeconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - s.t0).count();
  s.info.wallSeconds = res_.wallSeconds;
  if (s.outputs && s.ranks.root()) s.info.outputs = s.outputs->reports(); // the others' make parts only
  res_.files.clear();
  for (const auto& o : s.info.outputs) res_.files.insert(res_.files.end(), o.files.begin(), o.files.end());
  res_.files.push_back("summary.json");
}

void Run::writeFailed(const std::string& what) {
  res_.status = RunStatus::WriteFailure;
  res_.error = what;
  s_->info.status = "failed: " + what;
  record();
  try {
    writeSummaryJson(s_->summaryFile, *s_->view, s_->info);
  } catch (const WriteError&) {
    // The disk refuses it as well; the error above is the one to report.
  }
  ended_ = true;
}

/// Runs f; a write failure or a failed peer ends the run. Once ended, the ranks agree on how
/// (rank 0 knows a write failure the others saw as PeerFailed).
template <class F> void Run::guarded(F&& f) {
  try {
    f();
  } catch (const WriteError& e) {
    writeFailed(e.what());
  } catch (const fs::filesystem_error& e) { // a folder an output creates
    writeFailed(WriteError(e.path1().string(), e.code().message()).what());
  } catch (const PeerFailed&) {
    record(); // rank 0 failed and reports it; its status is agreed below
    ended_ = true;
  }
  if (ended_ && s_->ranks.active())
    res_.status = RunStatus(s_->ranks.agree(s_->ranks.root() ? int(res_.status) : 0));
  res_.ok = res_.status == RunStatus::Completed;
}

} // namespace talus
