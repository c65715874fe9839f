// `talus bench`: throughput (particle-steps per second per core), time per phase, memory.
#pragma once

#include "engine/communicator.h"
#include "io/scene/scene.h"

#include <memory>
#include <string>
#include <vector>

namespace talus {

struct BenchOptions {
  std::vector<std::string> cases{"elastic"}; ///< names from benchmarkCaseNames()
  std::vector<int> threads{1, 2};
  int steps = 40;   ///< timed steps after warm-up
  int warmup = 5;
  double scale = 1; ///< multiplies the particle count (approximately)
  double flip = 0;  ///< AFLIP blend of every case ([simulation] flip; 0: APIC)
  bool fbar = false; ///< F-bar in every case ([simulation] fbar)
};

/// One benchmark measurement.
struct BenchResult {
  std::string name;
  int threads = 1;
  size_t particles = 0, blocks = 0;
  int steps = 0;
  double particleStepsPerSecond = 0;
  double binShare = 0, p2gShare = 0, gridShare = 0, g2pShare = 0, otherShare = 0; ///< of wall time
  double bytesPerParticle = 0, scratchBytesPerParticle = 0, bytesPerBlock = 0;
  double secondsPerStep = 0;
  double efficiency = 0; ///< against the 1-thread run of the same case (0 when none)
};

std::vector<std::string> benchmarkCaseNames();
/// Whether a case names a scene file (ends in .toml) rather than a built-in case.
bool isSceneFileCase(const std::string& name);
/// The scene of a benchmark case, its particle count multiplied by about opt.scale, with opt's
/// AFLIP blend and F-bar.
SceneSetup benchmarkScene(const std::string& name, const BenchOptions& opt);
/// Steps run before timing a case: options.warmup, and more for a case whose state takes time to
/// set in (snow_flow's yielding).
int benchmarkWarmup(const std::string& name, const BenchOptions& options);

/// `mpirun -np N talus bench --ranks`: each case distributed over the N ranks (threads per rank:
/// the first of options.threads); rank 0 prints throughput, communication time and bytes.
int runRankBenchmarks(const BenchOptions& options, const std::shared_ptr<Communicator>& ranks);
/// Runs the cases; `print` writes the table to stdout as it goes.
std::vector<BenchResult> measureBenchmarks(const BenchOptions& options, bool print);
int runBenchmarks(const BenchOptions& options);

/// Time per step and grid memory of an elastic slab of `particles` particles (approximately)
/// in a domain `domainScale` times larger in each direction than the slab needs.
BenchResult measureScaling(double particleScale, double domainScale, int steps);

} // namespace talus
