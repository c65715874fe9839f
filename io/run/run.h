// A run in progress: the simulation with its outputs, frames, checkpoints and signals, advanced
// step by step by whoever drives it (`runScene` to the end time; the Python module from a script).
#pragma once

#include "io/run/run_driver.h"

#include <functional>
#include <memory>

namespace talus {

class Simulation;
struct PartBounds;

class Run {
public:
  /// Builds the simulation from the scene (its material groups move in), creates the output
  /// folder and the outputs [output] asks for, and with options.resume continues from the
  /// folder's checkpoint. Throws InputError when that checkpoint is missing or refused (before
  /// anything is written). A folder or file that cannot be written does not throw: the run
  /// ends at once with RunStatus::WriteFailure (see ended(), result()).
  Run(SceneSetup&& scene, const RunOptions& options);
  ~Run();
  Run(const Run&) = delete;
  Run& operator=(const Run&) = delete;

  /// One step toward the next frame or the end time, then what follows every step: the
  /// per-step outputs, a checkpoint when one is due or asked for (SIGUSR1), a frame when its
  /// time is reached, a stop signal. Returns false once the run has ended: at the end time
  /// (the final outputs are then written), on a numerical failure, a write failure, or a stop
  /// (signal or interrupt()). Calling it after the end does nothing; a run resumed at a frame's
  /// time writes that frame on its first call without stepping. Never throws the run's own
  /// failures: they are in result().
  bool step();
  /// Steps until the simulated time reaches t (or the end time, or the run ends); afterStep, if
  /// given, is called after every step. Returns false once the run has ended.
  bool advanceTo(double t, const std::function<void()>& afterStep = {});
  /// Ends the run as interrupted by `signal` (0: by its caller): writes a checkpoint and
  /// summary.json; a later Run with options.resume continues bit for bit.
  void interrupt(int signal = 0);
  /// Writes a checkpoint of the current state now (the run goes on).
  void checkpoint();

  bool ended() const { return ended_; }
  const Simulation& simulation() const { return *sim_; }
  /// Under ranks, on rank 0: how many particles its view of the whole run has room for. It is
  /// filled to write a frame, a checkpoint or the end's files and emptied after them (after the
  /// end it keeps the final state), so between writes rank 0 holds its own share of the
  /// particles. 0 on the other ranks and in one process (the simulation is its own view).
  size_t viewCapacity() const;
  double endTime() const { return endTime_; }
  /// The result so far; complete once ended().
  const RunResult& result() const { return res_; }

private:
  struct State;
  /// Before the first step (collective under ranks): every particle as seeded gathered to rank 0,
  /// which makes the output folder and starts the outputs; the other ranks' outputs make parts.
  /// Throws WriteError when the folder cannot be made.
  void startOutputs(const SceneSetup& scene, bool seededInParts);
  /// The state and the outputs' clocks from the run's checkpoint. Throws InputError when it is
  /// missing, damaged or of another scene.
  void resume();
  void afterStep();
  /// Frame s_->frame of the state now (collective under ranks), then the next frame's number.
  void writeFrame();
  /// What every rank must agree on after a step: a checkpoint asked for (SIGUSR1), a stop signal.
  struct Agreed {
    int checkpoint = 0, signal = 0;
  };
  /// Under ranks, after a step: this process's flags and the outputs' figures in one reduction,
  /// then the per-step outputs. Returns the flags every rank agrees on.
  Agreed stepOnRanks(Agreed mine);
  /// The per-step outputs under ranks, with the step size, the outputs rank 0 needs and every
  /// rank's maxima: parts exchanged (the maps' cells to their owners, the rest to rank 0), then
  /// what reads every particle.
  void stepOutputsOnRanks(double dt, uint32_t due, const PartBounds& b);
  /// Under ranks, before rank 0 writes a checkpoint or the end's files: the state of the cells
  /// the other processes own (OutputObserver::partsByOwner), gathered into rank 0's outputs.
  void gatherOutputState();
  /// Under ranks, after the start or a resume: rank 0's state of the outputs every process keeps
  /// alike (OutputObserver::sharesState: a probe's place, the series' clock) to every process.
  void shareOutputState();
  void finish();
  template <class F> void guarded(F&& f);
  void writeFailed(const std::string& what);
  void record();

  std::unique_ptr<State> s_;
  std::unique_ptr<Simulation> sim_;
  RunResult res_;
  double endTime_ = 0;
  bool ended_ = false;
};

} // namespace talus
