#include "io/run/progress_bar.h"

#include <algorithm>
#include <unistd.h>

namespace talus {

ProgressBar::ProgressBar(double endTime, FILE* stream, bool allowed)
    : endTime_(endTime), stream_(stream), enabled_(allowed && isatty(fileno(stream))),
      start_(std::chrono::steady_clock::now()), last_(start_ - std::chrono::seconds(1)) {}

void ProgressBar::update(double time, uint64_t steps, uint64_t particleSteps) {
  if (!enabled_) return;
  const auto now = std::chrono::steady_clock::now();
  if (now - last_ < std::chrono::milliseconds(200)) return;
  last_ = now;
  const double wall = std::chrono::duration<double>(now - start_).count();
  const double frac = std::clamp(time / endTime_, 0.0, 1.0);
  const int width = 24, filled = int(frac * width);
  char bar[width + 1];
  for (int i = 0; i < width; ++i) bar[i] = i < filled ? '#' : '.';
  bar[width] = 0;
  const double eta = frac > 0 ? wall * (1 - frac) / frac : 0;
  std::fprintf(stream_, "\r[%s] t %.3g/%.3g s  step %llu  %.2e particle-steps/s  ETA %d:%02d   ", bar, time,
               endTime_, (unsigned long long)steps, wall > 0 ? double(particleSteps) / wall : 0.0,
               int(eta) / 60, int(eta) % 60);
  std::fflush(stream_);
}

void ProgressBar::finish() {
  if (enabled_ && !finished_) std::fprintf(stream_, "\n");
  finished_ = true;
}

} // namespace talus
