// The interface every output implements: the run driver calls it at start, after every step, at
// every frame and at the end. An output that is not requested is never constructed, so it costs
// nothing (io/output_set.cpp decides which exist).
#pragma once

#include "engine/simulation.h"
#include "engine/state_archive.h"

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
  /// After the last step. `completed` is false when the run stopped on a numerical failure:
  /// particle state may then be non-finite, so "final state" outputs should be skipped.
  virtual void onFinish(const Simulation& sim, bool completed) {}

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
