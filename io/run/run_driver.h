// `talus run`: a scene from start to end time, writing frames, particles.h5 and summary.json.
#pragma once

#include "engine/communicator.h"
#include "io/scene/scene.h"

#include <functional>
#include <memory>

#include <cstdint>
#include <string>
#include <vector>

namespace talus {

struct RunOptions {
  std::string outDir;          ///< overrides [output].directory when not empty
  int threads = 0;             ///< 0 = all hardware threads
  bool progress = true;        ///< progress bar when stderr is a terminal
  bool resume = false;         ///< continue from outDir/checkpoint.h5 instead of starting anew
  /// Answer SIGINT/SIGTERM (stop after this step with a checkpoint) and SIGUSR1 (checkpoint now)
  /// for the run's duration (io/run/run_signals.h). The talus program sets it.
  bool handleSignals = false;
  /// MPI ranks (mpirun talus run): every rank runs runScene with the same scene, seeded in its
  /// part (SeedSlice) or whole; rank 0 writes every file from a view gathered from the ranks
  /// (Simulation::emptyView). Null: one process.
  std::shared_ptr<Communicator> ranks;
};

enum class RunStatus {
  Completed,
  NumericalFailure, ///< a guard stopped the run (NumericalError); outputs so far were written
  WriteFailure,     ///< an output could not be written; every file written before is intact
  Interrupted,      ///< SIGINT or SIGTERM: a checkpoint and summary.json were written
};

struct RunResult {
  std::string outDir;
  double wallSeconds = 0;
  RunStatus status = RunStatus::Completed;
  bool ok = true;               ///< status == Completed
  std::string error;            ///< what failed (NumericalFailure, WriteFailure)
  int signal = 0;               ///< the signal that interrupted the run
  uint64_t steps = 0;           ///< steps taken when the run ended
  double time = 0;              ///< simulated time reached
  double checkpointTime = -1;   ///< time of the newest checkpoint on disk (-1: none)
  std::vector<std::string> files; ///< everything the outputs wrote, relative to outDir
};

/// What a user should look at after a run, most telling first: a hazard map quick-look when
/// there are maps, else a plot, else summary.json (relative to the output directory).
std::vector<std::string> filesToOpenFirst(const RunResult& r);

/// Runs a built scene to its end time; the scene's material groups move into the simulation, so
/// the caller hands the scene over (std::move). Numerical failures, write failures and
/// interruptions are reported in the result (and, when the disk allows, in summary.json) instead
/// of thrown; outputs already written stay in place. A missing or refused checkpoint to resume
/// from throws InputError.
RunResult runScene(SceneSetup&& scene, const RunOptions& options);

} // namespace talus
