// `talus bench`: throughput (particle-steps per second per core), time per phase, memory.
#pragma once

#include <string>
#include <vector>

namespace talus {

struct BenchOptions {
  std::vector<std::string> cases{"elastic"}; ///< names from benchmarkCaseNames()
  std::vector<int> threads{1, 2};
  int steps = 40;   ///< timed steps after warm-up
  int warmup = 5;
  double scale = 1; ///< multiplies the particle count (approximately)
};

std::vector<std::string> benchmarkCaseNames();
int runBenchmarks(const BenchOptions& options);

} // namespace talus
