// Run's state besides the simulation, shared by the files that implement Run (run.cpp: the
// step and what follows it; run_outputs_on_ranks.cpp: the per-step outputs under ranks). Private
// to io/run.
#pragma once

#include "io/output/output_set.h"
#include "io/run/checkpoint.h"
#include "io/run/progress_bar.h"
#include "io/run/run.h"
#include "io/run/run_ranks.h"
#include "io/run/run_signals.h"
#include "io/run/run_summary.h"

#include <chrono>
#include <limits>
#include <malloc.h>
#include <memory>
#include <optional>
#include <tbb/global_control.h>
#include <tbb/task_arena.h>

namespace talus {

/// Rank 0's heap while it writes a frame or the end's files. Rank 0 holds glibc's mmap threshold
/// at 128 kB (Run's constructor: the view's arrays are mapped apart and returned whole), so
/// every larger buffer of a write (a node-sum block list growing, a film picture, a map) was
/// mapped, faulted in page by page and unmapped again: the VDB volume frames took 0.83–1.03 s
/// on 2 ranks against 0.21 s in one process, the end's maps 3.4–4.0 s against 2.3–2.7 s. While
/// this lives, blocks up to 32 MB come from the heap and stay there; after, the threshold is
/// held at 128 kB again and the heap's free memory goes back to the system (malloc_trim), so
/// between writes rank 0 holds what it did. Nothing when `on` is false (the other ranks, one
/// process: they never fixed the threshold).
class WriteHeap {
public:
  explicit WriteHeap(bool on) : on_(on) {
    if (on_) mallopt(M_MMAP_THRESHOLD, 32 << 20), mallopt(M_TRIM_THRESHOLD, 64 << 20);
  }
  ~WriteHeap() {
    if (!on_) return;
    mallopt(M_MMAP_THRESHOLD, 128 << 10), mallopt(M_TRIM_THRESHOLD, 128 << 10); // glibc's defaults
    malloc_trim(0);
  }
  WriteHeap(const WriteHeap&) = delete;
  WriteHeap& operator=(const WriteHeap&) = delete;

private:
  bool on_;
};

/// Everything of the run besides the simulation: the scene's settings, the outputs, the view
/// rank 0 writes from, the clocks of frames and checkpoints.
struct Run::State {
  State(const SceneSetup& scene, const RunOptions& o)
      : opt(o), ranks(o.ranks), output(scene.output), materialNames(scene.materialNames),
        identity{scene.hash, scene.stateKeys}, interval(scene.output.frameInterval),
        checkpointEvery(scene.output.checkpointInterval < 0 ? scene.endTime / 10
                                                            : scene.output.checkpointInterval) {}

  RunOptions opt;
  RunRanks ranks;
  OutputSettings output;
  std::vector<std::string> materialNames;
  CheckpointIdentity identity;
  int threads = 1; ///< TBB threads of this process
  std::unique_ptr<tbb::global_control> threadLimit;
  std::unique_ptr<Simulation> viewed; ///< rank 0's whole view under ranks (else null)
  /// Every rank writes its own particles into files rank 0 lists or lays out (checkpoint parts,
  /// frames): under ranks that all see the output folder.
  bool writesInParts = false;
  Simulation* view = nullptr;         ///< what outputs read: viewed, or the simulation itself
  RunInfo info;
  std::optional<OutputSet> outputs;
  std::optional<RunSignals> signals;
  std::unique_ptr<ProgressBar> bar;
  RootLoadBalance balance;
  std::chrono::steady_clock::time_point t0 = std::chrono::steady_clock::now();
  std::string summaryFile, checkpointFile;
  int frame = 0;
  double interval, checkpointEvery;
  double nextCheckpoint = std::numeric_limits<double>::infinity();

  /// Collective under ranks: rank 0's view gets every particle, for files written from it; the
  /// view holds them only until releaseView, so between writes rank 0 holds its own share.
  void gatherView(Simulation& sim) {
    if (!ranks.active()) return;
    sim.gatherInto(viewed.get());
    ++info.wholeGathers;
  }
  void releaseView() {
    if (viewed) viewed->releaseParticles();
  }
  /// Runs f on `cores` threads when that is more than the run's own: the cores the other ranks
  /// lend rank 0 for the end's files (RunRanks::onRootWithNodeCores).
  template <class F> void withThreads(int cores, F&& f) {
    if (cores <= threads) return f();
    auto limit = [](int n) { return std::make_unique<tbb::global_control>(tbb::global_control::max_allowed_parallelism, size_t(n)); };
    threadLimit = limit(cores); // the old limit goes after the new one is in force
    struct Back {
      State& s;
      std::unique_ptr<tbb::global_control> (*limit)(int);
      ~Back() { s.threadLimit = limit(s.threads); }
    } back{*this, +limit};
    // Another limit in force (a caller's own, as the tests keep) still holds.
    tbb::task_arena(int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism))).execute(f);
  }
};

} // namespace talus
