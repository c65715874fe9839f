// The interface every output implements: the run driver calls it at start, after every step, at
// every frame and at the end. An output that is not requested is never constructed, so it costs
// nothing (io/output_set.cpp decides which exist).
#pragma once

#include "engine/communicator.h"
#include "engine/simulation.h"
#include "engine/state_archive.h"
#include "io/common/write_error.h"
#include "io/output/step_parts.h"

#include <optional>
#include <string>
#include <vector>

namespace talus {

class OutputObserver {
public:
  virtual ~OutputObserver() = default;

  /// Short identifier used in summary.json ("vdb_frames", "hazard_maps", ...).
  virtual std::string name() const = 0;

  /// Before the first step (time 0, the seeded state; the grid holds no data yet).
  virtual void onStart(const Simulation& sim) {}
  /// After every step; dt is the step just taken (s). The grid holds that step's node data.
  virtual void onStep(const Simulation& sim, double dt) {}
  /// At every frame time (frame 0 is the initial state).
  virtual void onFrame(const Simulation& sim, int index) {}
  /// Whether the frame's file is written by every process from its own particles, collectively
  /// (onFrameParts), instead of by rank 0 from a view of every particle (onFrame).
  virtual bool framesInParts() const { return false; }
  /// Collective on every process with its own particles, for an output whose framesInParts():
  /// this frame's file, byte for byte one process's. Returns on rank 0 the first failure of any
  /// process (nothing elsewhere); onFrame is the same call for one process.
  virtual std::optional<WriteError> onFrameParts(Communicator& comm, const Simulation& local, int index) {
    return std::nullopt;
  }
  /// After the last step. `completed` is false when the run stopped on a numerical failure:
  /// particle state may then be non-finite, so "final state" outputs should be skipped.
  virtual void onFinish(const Simulation& sim, bool completed) {}

  /// Whether the output reads the particles after every step (frame formats read them at
  /// frames only). Such an output steps in parts (io/output/step_parts.h): its per-step work
  /// needs only exact reductions over the particles. The driver then, after every step, asks
  /// rank 0 partDue(), calls part() on every process with its own particles when due, and calls
  /// onStepParts() on rank 0 with every part (none when not due). Without ranks the same calls
  /// run with one part, so one process writes the same bytes; onStep() is that process's
  /// shortcut (stepOwnPart). No process gathers every particle after a step.
  virtual bool readsEveryStep() const { return false; }
  /// Before the run on processes other than rank 0: what part() needs (the scene, not particles).
  virtual void prepareParts(const Simulation& sim) {}
  /// After every step, on every process with its own particles, before the parts: what an output
  /// in parts must not miss between its parts (a section's crossings) is added up here, on the
  /// process that holds the particles. One process calls it with all of them.
  virtual void stepLocal(const Simulation& local, double dt) {}
  /// Whether stepLocal keeps a running total on each process: under ranks, before rank 0 saves a
  /// checkpoint or writes the end, the others hand it over with ownedResult(true) and rank 0 adds
  /// it in mergeResults(true), as for the outputs by owner.
  virtual bool accumulatesOnRanks() const { return false; }
  /// On rank 0, after a step: whether this step's parts are needed.
  virtual bool partDue(const Simulation& sim) const { return false; }
  /// This process's part from its own particles, appended to `out`; `b` holds every process's
  /// maxima. `keep`: the part is rank 0's own (or one process's), merged next by this same
  /// object, which may keep it in place and append nothing.
  virtual void part(const Simulation& local, const PartBounds& b, bool keep, std::vector<char>& out) {}
  /// On rank 0: the step from every process's part (rank order; empty when not due).
  virtual void onStepParts(const Simulation& sim, double dt, const PartBounds& b,
                           const std::vector<std::string_view>& parts) {}

  /// Parts by owner: an output over map cells whose cells are owned by the ranks (bands of rows
  /// in turn, ownerOfRow) returns true. Every process then folds the cells it owns: partByOwner()
  /// replaces part(), and onStepParts() runs on every process with the parts of its own cells.
  /// Rank 0 gathers the folded cells only when it writes them (results below), so no process
  /// adds every cell of the map. One process owns every cell and runs the same calls.
  virtual bool partsByOwner() const { return false; }
  /// Row `row`'s owner among `ranks` processes: bands of kRowsPerOwner rows in turn, so a flow's
  /// rows spread over the ranks while a rank's particles (a compact patch of blocks) touch the
  /// rows of few owners: one message to each (docs/scaling.md, the model).
  static constexpr int kRowsPerOwner = 8;
  static int ownerOfRow(int row, int ranks) { return (row / kRowsPerOwner) % ranks; }
  /// This process's part for every other process r (appended to outs[r]; outs.size() is the
  /// number of processes). Its own cells' sums stay in place for its onStepParts.
  virtual void partByOwner(const Simulation& local, const PartBounds& b, int self, std::vector<std::vector<char>>& outs) {}
  /// An output by owner whose processes keep the same state (a probe's place, the series'
  /// clock): after the start and after a resume, rank 0's shareState() goes to every other
  /// process's takeState().
  virtual bool sharesState() const { return false; }
  virtual void shareState(std::vector<char>& out) const {}
  /// @throw std::runtime_error if `in` is not what shareState writes
  virtual void takeState(std::string_view in) {}
  /// After onStepParts, on every process alike: whether rank 0 needs this step's folded cells
  /// (a film frame), sent by results(false).
  virtual bool resultDue() const { return false; }
  /// On a process other than rank 0: its owned cells' results, appended to `out`: the step's
  /// (state false, when resultDue) or the state accumulated so far (true: before rank 0 writes
  /// a checkpoint or the end's files; an output that accumulatesOnRanks hands its totals over).
  virtual void ownedResult(bool state, std::vector<char>& out) {}
  /// On rank 0: the other processes' results (rank order, from rank 1); with `state` false it
  /// writes what was due (one process calls it with none).
  /// @throw std::runtime_error if a result does not hold whole cells of this output
  virtual void mergeResults(const Simulation& sim, bool state, const std::vector<std::string_view>& others) {}

  /// onStep of an output in parts in one process: its own part, merged alone.
  void stepOwnPart(const Simulation& sim, double dt) {
    std::vector<char> own;
    const PartBounds b = PartBounds::of(sim);
    part(sim, b, true, own);
    onStepParts(sim, dt, b, {std::string_view(own.data(), own.size())});
    if (resultDue()) mergeResults(sim, false, {});
  }

  /// Checkpointing: the state accumulated since the start (maxima, rows, pending volumes), so a
  /// resumed run writes the same files as an uninterrupted one. On resume the driver calls
  /// onStart on the initial state first, then load.
  virtual void save(StateArchive& a, const std::string& prefix) const {}
  virtual void load(const StateArchive& a, const std::string& prefix) {}

  /// Entries this output adds to summary.json: (key, JSON value), e.g. the peak collider loads.
  virtual std::vector<std::pair<std::string, std::string>> summary() const { return {}; }

  /// Files written so far, relative to the output directory.
  const std::vector<std::string>& files() const { return files_; }

  /// The list travels in checkpoints, so a resumed run's summary.json names the files written
  /// before the interruption too.
  void saveFiles(StateArchive& a, const std::string& name) const {
    std::string text;
    for (const auto& f : files_) text += f + '\n';
    a.putVector(name, std::vector<char>(text.begin(), text.end()));
  }
  void loadFiles(const StateArchive& a, const std::string& name) {
    std::vector<char> text;
    a.getVector(name, text);
    files_.clear();
    std::string f;
    for (char c : text)
      if (c != '\n') f += c;
      else recordFile(f), f.clear();
  }

protected:
  void recordFile(const std::string& relativePath) {
    for (const auto& f : files_)
      if (f == relativePath) return;
    files_.push_back(relativePath);
  }

private:
  std::vector<std::string> files_;
};

} // namespace talus
