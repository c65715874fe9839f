// Helpers shared by the validation cases (validation_cases.cpp, validation_dam_break.cpp):
// building a Simulation from an inline scene at a given Resolution, timing, and the front of a
// quasi-2-D flow, a centred moving average. Internal to talus_validation.
#pragma once

#include "engine/simulation.h"
#include "tools/validation_cases.h"

#include <chrono>
#include <memory>
#include <string>
#include <vector>

namespace talus::validation::detail {

using Clock = std::chrono::steady_clock;

/// The scene in `toml` at r's particles per cell and CFL; records the particle count in cost.
std::unique_ptr<Simulation> build(const std::string& toml, const Resolution& r, RunCost& cost);
/// Records steps and wall seconds since t0.
void finish(const Simulation& sim, Clock::time_point t0, RunCost& cost);
std::string format(const char* fmt, ...) __attribute__((format(printf, 1, 2)));

/// The first time a record v(t) exceeds `level`, linear between the samples around the crossing
/// (so an arrival is not rounded up to a sample); t[0] when it starts above, -1 when it never is.
double firstAbove(const std::vector<double>& t, const std::vector<double>& v, double level);

/// Centred moving average of v over 2 half + 1 samples (fewer at the ends), summed in index order.
std::vector<double> movingAverage(const std::vector<double>& v, int half);

/// Front of a quasi-2-D flow (Lube's "farthest point of the continuous deposit"): bins of width
/// `bin` count when their thickness (particle volume / (bin * channel width)) reaches
/// `threshold`, a physical threshold so the front means the same at every dx. From the first
/// such bin in x, the run continues across gaps of at most maxGap (0: none) and ends at the far
/// edge of its last bin. A thin rear (a drained reservoir) neither starts nor breaks the run.
double contiguousFront(const Simulation& sim, double bin, double channelWidth, double threshold, double maxGap = 0);

} // namespace talus::validation::detail
