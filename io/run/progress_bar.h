// One-line progress on a terminal: simulated time, steps, particle-steps/s, ETA. Silent otherwise.
#pragma once

#include <chrono>
#include <cstdint>
#include <cstdio>

namespace talus {

class ProgressBar {
public:
  /// Enabled only when `stream` is a terminal (and `allowed`).
  ProgressBar(double endTime, FILE* stream = stderr, bool allowed = true);
  void update(double time, uint64_t steps, uint64_t particleSteps);
  /// Ends the line (once); the destructor does it when a failure skipped it.
  void finish();
  ~ProgressBar() { finish(); }

private:
  double endTime_;
  FILE* stream_;
  bool enabled_, finished_ = false;
  std::chrono::steady_clock::time_point start_, last_;
};

} // namespace talus
