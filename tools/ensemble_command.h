// `talus ensemble SCENE --vary KEY=LOW:HIGH ... --samples N [--method lhs|grid|morris]`: runs
// the scene's members (hazard/ensemble_runner.h) and summarises them
// (hazard/ensemble_aggregate.h). docs/hazard.md.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace talus {

struct EnsembleOptions {
  std::string scene, out = "talus_ensemble", method = "lhs", avaframe;
  std::vector<std::string> vary, sets;
  size_t samples = 0;
  uint64_t seed = 12345; ///< AvaFrame's probAna sampleSeed default
  int threads = 1;       ///< per member
  int jobs = 0;          ///< members at a time; 0 = cores / threads
  bool aggregateOnly = false;
};

CLI::App* addEnsembleCommand(CLI::App& app, EnsembleOptions& o);
int runEnsembleCommand(const EnsembleOptions& o);

} // namespace talus
