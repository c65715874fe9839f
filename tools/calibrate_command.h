// `talus calibrate SCENE --vary KEY=LOW:HIGH ... --observed KIND=... [--budget N]`: back-analysis
// of an observed event (hazard/calibration.h), members run as ensemble members; writes the
// calibrated scene beside the results. docs/hazard.md, "Calibration".
#pragma once

#include <cstdint>
#include <string>
#include <vector>

namespace CLI {
class App;
}

namespace talus {

struct CalibrateOptions {
  std::string scene, out = "talus_calibration", avaframe, rasterResult;
  std::vector<std::string> vary, observed, weights, sets;
  size_t budget = 20, initial = 0, screen = 2;
  double screenKeep = 0.1, tolerance = 0.05, eiStop = 1e-3;
  uint64_t seed = 1;
  int threads = 1; ///< per member
  int jobs = 0;    ///< members at a time; 0 = cores / threads
};

CLI::App* addCalibrateCommand(CLI::App& app, CalibrateOptions& o);
int runCalibrateCommand(const CalibrateOptions& o);

} // namespace talus
