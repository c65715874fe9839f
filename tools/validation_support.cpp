#include "tools/validation_support.h"

#include "io/scene/scene.h"

#include <cmath>
#include <cstdarg>
#include <cstdio>
#include <map>

namespace talus::validation::detail {

std::unique_ptr<Simulation> build(const std::string& toml, const Resolution& r, RunCost& cost) {
  SceneSetup s = loadSceneString(toml, "validation.toml",
                                 {"simulation.particles_per_cell=" + std::to_string(r.particlesPerCell),
                                  "simulation.cfl=" + std::to_string(r.cfl)});
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

double contiguousFront(const Simulation& sim, double bin, double channelWidth, double threshold) {
  std::map<int, double> volume;
  const double ox = sim.settings().origin.x();
  for (const auto* g : sim.groups())
    for (size_t i = 0; i < g->size(); ++i)
      volume[int(std::floor((double(g->particles.x[i].x()) + ox) / bin))] += double(g->particles.mass[i]) / g->density();
  double front = 0;
  int expect = volume.empty() ? 0 : std::min(0, volume.begin()->first);
  for (const auto& [b, v] : volume) {
    if (b != expect || v / (bin * channelWidth) < threshold) break;
    front = (b + 1) * bin;
    ++expect;
  }
  return front;
}

} // namespace talus::validation::detail
