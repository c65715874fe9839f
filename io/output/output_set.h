// The outputs a scene requested, built from its [output] section, and the clock on each of them.
#pragma once

#include "io/output/output_observer.h"
#include "io/output/output_settings.h"
#include "io/output/run_context.h"

#include <memory>
#include <string>
#include <vector>

namespace talus {

/// Wall time one output took over the run and the files it wrote (relative to the output dir).
struct OutputReport {
  std::string name;
  double seconds = 0;
  std::vector<std::string> files;
  std::vector<std::pair<std::string, std::string>> summary; ///< top-level summary.json entries
};


class OutputSet {
public:
  /// Constructs only the outputs `settings` asks for. `outDir` must exist.
  OutputSet(const OutputSettings& settings, const RunContext& run, const std::string& outDir);
  /// Under ranks, on processes other than rank 0: only the outputs that read the particles after
  /// every step, which step in parts (OutputObserver::readsEveryStep), prepared from `sim`'s
  /// scene, and, given rank 0's `framesDir` (the output folder, which this process sees too),
  /// the frame formats written in parts (OutputObserver::framesInParts). Touches no file but
  /// the frames folder.
  struct PartsOnly {};
  OutputSet(PartsOnly, const OutputSettings& settings, const RunContext& run, const Simulation& sim,
            const std::string& framesDir = "");
  ~OutputSet();

  void start(const Simulation& sim);
  /// After each step in one process; the step size is the time since the previous call.
  void step(const Simulation& sim);

  /// A step under ranks, in several calls (io/run/run.cpp). Every process: the step size since
  /// the previous step (as step()), then stepLocal with its own particles. Rank 0: which outputs
  /// in parts are due (bit i: the i-th of them).
  double stepTime(const Simulation& sim);
  void stepLocal(const Simulation& local, double dt);
  uint32_t partsDue(const Simulation& sim) const;
  /// Every process (`self` of `ranks`): its parts of the due outputs from its own particles, one
  /// buffer per process to send them to: rank 0 gets every output's, the others those of the
  /// outputs by owner (OutputObserver::partsByOwner).
  std::vector<std::vector<char>> parts(const Simulation& local, uint32_t due, const PartBounds& b, int self, int ranks);
  /// Every process: the step of the outputs in parts from the buffers every process sent it
  /// (rank order; none when nothing was due); rank 0 steps them all, the others those by owner.
  /// @throw std::runtime_error if a buffer does not hold the due parts
  void mergeParts(const Simulation& sim, double dt, uint32_t due, const PartBounds& b,
                  const std::vector<std::string_view>& buffers);
  /// After mergeParts, the same on every process: whether rank 0 needs the outputs by owner's
  /// folded cells of this step (a film frame), which it then gathers from results(false).
  bool resultsDue(int ranks) const;
  /// A process other than rank 0: its owned cells' results of the outputs by owner, the step's
  /// or (state) all they accumulated with the running totals of those that accumulate on ranks
  /// (handed over: they start again from zero), as one buffer for rank 0.
  std::vector<char> results(bool state, int ranks);
  /// Rank 0: merges every process's results buffer (rank order; rank 0's own empty) and writes
  /// what was due this step (with none, what its own outputs hold: one process, or no owners).
  /// Before a checkpoint or the end, with `state`, after a gather of results(true).
  /// @throw std::runtime_error if a buffer does not hold the results
  void mergeResults(const Simulation& sim, bool state, const std::vector<std::string_view>& buffers, int ranks);
  /// Whether some output by owner keeps the same state on every process (the same everywhere).
  bool sharesState(int ranks) const;
  /// Rank 0, after the start or a resume: that state, as one buffer for every other process,
  /// which takes it with takeSharedState.
  /// @throw std::runtime_error (takeSharedState) if the buffer does not hold it
  std::vector<char> sharedState(int ranks);
  void takeSharedState(std::string_view buffer, int ranks);
  /// On rank 0 (or one process): frame `index` from `sim`, which holds every particle. With
  /// `partsWritten`, the outputs whose frames are written in parts are left out (frameParts
  /// wrote them).
  void frame(const Simulation& sim, int index, bool partsWritten = false);
  /// Collective on every process with its own particles: the frame files written in parts
  /// (OutputObserver::framesInParts). Returns on rank 0 the first failure.
  std::optional<WriteError> frameParts(Communicator& comm, const Simulation& local, int index);
  void finish(const Simulation& sim, bool completed);

  /// Checkpointing of every output's accumulated state (see OutputObserver::save).
  void save(StateArchive& a) const;
  void load(const StateArchive& a);
  /// A resumed process other than rank 0: only the outputs' clock (its parts keep no state).
  void loadClock(const StateArchive& a);

  /// Identifiers of the constructed outputs, in call order.
  std::vector<std::string> names() const;
  std::vector<OutputReport> reports() const;

private:
  /// The outputs that may read the particles after every step (series, maps, peak files, run-up).
  void addStepOutputs(const OutputSettings& o, const RunContext& run, const std::string& outDir);
  /// The frame formats; `inPartsOnly`: only those written in parts (the other ranks' set).
  void addFrameOutputs(const OutputSettings& o, const RunContext& run, const std::string& outDir, bool inPartsOnly);
  template <class F> void each(F&& f);
  template <class F> void eachInParts(F&& f);
  /// Whether `o` steps by owner among `ranks` processes (one process owns everything).
  bool byOwner(const OutputObserver& o, int ranks) const;
  /// Whether rank 0 gathers `o`'s state from the others before it saves or ends.
  bool gathersState(const OutputObserver& o, int ranks) const;
  std::vector<std::unique_ptr<OutputObserver>> outputs_;
  bool root_ = true; ///< merges the parts (rank 0, or one process): keeps its own in place
  std::vector<double> seconds_;
  double lastTime_ = 0;
};

} // namespace talus
