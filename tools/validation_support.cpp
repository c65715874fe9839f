#include "tools/validation_support.h"

#include "io/scene/scene.h"

#include <algorithm>
#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <map>

namespace talus::validation::detail {

std::unique_ptr<Simulation> build(const std::string& toml, const Resolution& r, RunCost& cost) {
  SceneSetup s = loadSceneString(toml, "validation.toml",
                                 {"simulation.particles_per_cell=" + std::to_string(r.particlesPerCell),
                                  "simulation.cfl=" + std::to_string(r.cfl),
                                  "simulation.flip=" + std::to_string(r.flip),
                                  std::string("simulation.fbar=") + (r.fbar ? "true" : "false")});
  auto sim = std::make_unique<Simulation>(s.settings, std::move(s.groups));
  cost.particles = sim->particleCount();
  return sim;
}

void finish(const Simulation& sim, Clock::time_point t0, RunCost& cost) {
  cost.steps = sim.steps();
  cost.wallSeconds = std::chrono::duration<double>(Clock::now() - t0).count();
}

std::string format(const char* fmt, ...) {
  char buf[4096];
  va_list ap;
  va_start(ap, fmt);
  std::vsnprintf(buf, sizeof buf, fmt, ap);
  va_end(ap);
  return buf;
}

std::vector<double> movingAverage(const std::vector<double>& v, int half) {
  std::vector<double> out;
  for (int i = 0; i < int(v.size()); ++i) {
    double sum = 0;
    int n = 0;
    for (int j = std::max(0, i - half); j <= std::min(int(v.size()) - 1, i + half); ++j) sum += v[size_t(j)], ++n;
    out.push_back(sum / n);
  }
  return out;
}

double firstAbove(const std::vector<double>& t, const std::vector<double>& v, double level) {
  for (size_t i = 0; i < v.size(); ++i)
    if (v[i] > level) return i == 0 ? t[0] : t[i - 1] + (t[i] - t[i - 1]) * (level - v[i - 1]) / (v[i] - v[i - 1]);
  return -1;
}

double contiguousFront(const Simulation& sim, double bin, double channelWidth, double threshold, double maxGap) {
  std::map<int, double> volume;
  const double ox = sim.settings().origin.x();
  for (const auto* g : sim.groups())
    for (size_t i = 0; i < g->size(); ++i)
      volume[int(std::floor((double(g->particles.x[i].x()) + ox) / bin))] += double(g->particles.mass[i]) / g->density();
  const int gapBins = int(std::floor(maxGap / bin + 1e-9));
  bool started = false;
  int last = 0;
  for (const auto& [b, v] : volume) {
    if (v / (bin * channelWidth) < threshold) continue; // thin bins neither start nor extend the run
    if (started && b - last - 1 > gapBins) break;
    started = true, last = b;
  }
  return started ? (last + 1) * bin : 0.0;
}

} // namespace talus::validation::detail
