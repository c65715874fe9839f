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
  ~OutputSet();

  void start(const Simulation& sim);
  /// After each step; the step size is the time since the previous call.
  void step(const Simulation& sim);
  void frame(const Simulation& sim, int index);
  void finish(const Simulation& sim, bool completed);

  /// Checkpointing of every output's accumulated state (see OutputObserver::save).
  void save(StateArchive& a) const;
  void load(const StateArchive& a);

  /// Identifiers of the constructed outputs, in call order.
  std::vector<std::string> names() const;
  std::vector<OutputReport> reports() const;

private:
  template <class F> void each(F&& f);
  std::vector<std::unique_ptr<OutputObserver>> outputs_;
  std::vector<double> seconds_;
  double lastTime_ = 0;
};

} // namespace talus
