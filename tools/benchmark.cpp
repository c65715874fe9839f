#include "tools/benchmark.h"

#include "io/scene/scene.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <map>
#include <stdexcept>
#include <tbb/global_control.h>

namespace talus {

namespace {

struct Case {
  std::string description;
  std::string toml; // %DX% is replaced by the grid spacing for the requested scale
  double dx;
  int warmup = 0; // steps before timing, beyond BenchOptions::warmup: for a state that takes time to set in
};

// An elastic slab (50 x 25 x 25 cells, 8 particles per cell: 250k particles) dropped onto a
// slip floor, so stresses and contacts are realistic rather than a rigid translation.
const char* kElastic = R"(
[simulation]
dx = %DX%
particles_per_cell = 8
end_time = 10
[domain]
min = [0, 0, 0]
max = [1.4, 0.9, 0.8]
walls = "slip"
[[materials]]
name = "jelly"
model = "elastic"
density = 1000
youngs_modulus = 2e5
poisson_ratio = 0.3
[[bodies]]
material = "jelly"
shape = "box"
min = [0.2, 0.2, 0.06]
max = [1.2, 0.7, 0.56]
velocity = [0.5, 0, -1]
)";

// A 3-D column collapsing on a rough floor: 50 x 25 x 25 cells x 8 = 250k particles of the
// material %MATERIAL% stands for, most of them yielding every step.
const char* kCollapse = R"(
[simulation]
dx = %DX%
particles_per_cell = 8
end_time = 10
[domain]
min = [0, 0, 0]
max = [3.0, 0.9, 0.8]
walls = "slip"
[terrain]
plane = { point = [0, 0, 0.02], normal = [0, 0, 1] }
boundary = "friction"
friction = 0.5
[[materials]]
name = "column"
%MATERIAL%
[[bodies]]
material = "column"
shape = "box"
min = [0.02, 0.2, 0.02]
max = [1.02, 0.7, 0.52]
velocity = [1, 0, 0]
)";

// Cohesionless Drucker-Prager sand, phi 30.
const char* kSand = R"(model = "drucker_prager"
density = 1600
youngs_modulus = 1e6
poisson_ratio = 0.3
friction_angle = 30)";

// Flowing snow: Modified Cam Clay, Table 1 but for a 10 Pa preconsolidation (snow as loose as it
// is once an avalanche has broken it up). Timed after 160 steps, once the column has started to
// slump: then three quarters of the particles yield every step (at the start, under a fifth), as
// on Wolfsgruben.
const char* kLooseSnow = R"(preset = "snow"
preconsolidation_pressure = 10)";

// Issue 15's lab box, measured against the paper group's code on this machine: a cohesionless
// Drucker-Prager box 0.8 x 0.8 x 0.42 m (40 x 40 x 21 cells x 8 = 268 800 particles) collapsing in
// a 2 x 1 x 0.6 m domain with friction walls (mu 0.4).
const char* kBox = R"(
[simulation]
dx = %DX%
particles_per_cell = 8
end_time = 10
[domain]
min = [0, 0, 0]
max = [2.0, 1.0, 0.6]
walls = { law = "friction", friction = 0.4 }
[[materials]]
name = "sand"
model = "drucker_prager"
density = 1600
youngs_modulus = 1e6
poisson_ratio = 0.3
friction_angle = 30
[[bodies]]
material = "sand"
shape = "box"
min = [0, 0.1, 0]
max = [0.8, 0.9, 0.42]
)";

// A Table 1 snow block (Modified Cam Clay) hit by a rock block (Drucker-Prager): compaction.
const char* kSnow = R"(
[simulation]
dx = %DX%
particles_per_cell = 8
end_time = 10
[domain]
min = [0, 0, 0]
max = [1.4, 0.9, 1.2]
walls = "slip"
[[materials]]
name = "snow"
preset = "snow"
[[materials]]
name = "rock"
preset = "rock"
[[bodies]]
material = "snow"
shape = "box"
min = [0.2, 0.2, 0.0]
max = [1.2, 0.7, 0.5]
[[bodies]]
material = "rock"
shape = "box"
min = [0.5, 0.35, 0.55]
max = [0.7, 0.55, 0.75]
velocity = [0, 0, -20]
)";

// A 3-D dam break of softened Tait water (c = 30 m/s): 250k particles.
const char* kWater = R"(
[simulation]
dx = %DX%
particles_per_cell = 8
end_time = 10
[domain]
min = [0, 0, 0]
max = [2.0, 0.5, 1.1]
walls = "slip"
[[materials]]
name = "water"
model = "water"
density = 1000
sound_speed = 30
[[bodies]]
material = "water"
shape = "box"
min = [0, 0, 0]
max = [0.5, 0.5, 1.0]
)";

std::string substitute(std::string s, const std::string& key, const std::string& value) {
  for (size_t p; (p = s.find(key)) != std::string::npos;) s.replace(p, key.size(), value);
  return s;
}

const std::map<std::string, Case>& cases() {
  static const std::map<std::string, Case> c{
      {"elastic", {"elastic slab falling on a slip floor", kElastic, 0.02}},
      {"granular", {"Drucker-Prager column collapsing on a rough floor", substitute(kCollapse, "%MATERIAL%", kSand), 0.02}},
      {"box", {"issue 15's Drucker-Prager box in friction walls", kBox, 0.02}},
      {"snow", {"Cam Clay snow block hit by a rock block", kSnow, 0.02}},
      {"snow_flow", {"loose Cam Clay snow column collapsing on a rough floor", substitute(kCollapse, "%MATERIAL%", kLooseSnow), 0.02, 155}},
      {"water", {"Tait water dam break", kWater, 0.02}},
      {"terrain", {"the default scene: rock avalanche into snow on generated terrain", "", 4.0}},
  };
  return c;
}

} // namespace

std::vector<std::string> benchmarkCaseNames() {
  std::vector<std::string> n;
  for (const auto& [k, v] : cases()) n.push_back(k);
  return n;
}

namespace {
const Case& benchmarkCase(const std::string& name) {
  auto it = cases().find(name);
  if (it == cases().end()) throw std::runtime_error("unknown benchmark case '" + name + "'");
  return it->second;
}
} // namespace

bool isSceneFileCase(const std::string& name) { return name.size() > 5 && name.substr(name.size() - 5) == ".toml"; }

int benchmarkWarmup(const std::string& name, const BenchOptions& opt) {
  return opt.warmup + (isSceneFileCase(name) ? 0 : benchmarkCase(name).warmup);
}

SceneSetup benchmarkScene(const std::string& name, const BenchOptions& opt) {
  if (isSceneFileCase(name)) {
    // A user's scene as it stands; --scale refines its own dx, --flip and --fbar apply when given.
    std::vector<std::string> set;
    if (opt.flip > 0) set.push_back("simulation.flip=" + std::to_string(opt.flip));
    if (opt.fbar) set.push_back("simulation.fbar=true");
    if (opt.scale != 1) {
      const double dx = loadSceneFile(name, set).settings.dx / std::cbrt(opt.scale);
      char dxs[64];
      std::snprintf(dxs, sizeof dxs, "simulation.dx=%.9g", dx);
      set.push_back(dxs);
    }
    return loadSceneFile(name, set);
  }
  const Case& c = benchmarkCase(name);
  char dxs[32], flips[48];
  std::snprintf(dxs, sizeof dxs, "%.6g", c.dx / std::cbrt(opt.scale));
  std::snprintf(flips, sizeof flips, "simulation.flip=%.6g", opt.flip);
  std::vector<std::string> set{flips, std::string("simulation.fbar=") + (opt.fbar ? "true" : "false")};
  if (!c.toml.empty()) return loadSceneString(substitute(c.toml, "%DX%", dxs), "bench:" + name, set);
  set.push_back("simulation.dx=" + std::string(dxs));
  return loadSceneString(defaultSceneText(), "bench:" + name, set);
}

namespace {

BenchResult timeSteps(const std::string& name, Simulation& sim, int threads, int warmup, int steps) {
  for (int i = 0; i < warmup; ++i) sim.step();
  const PhaseTimes before = sim.phaseTimes();
  const uint64_t ps0 = sim.particleSteps();
  const auto t0 = std::chrono::steady_clock::now();
  for (int i = 0; i < steps; ++i) sim.step();
  const double wall = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  const PhaseTimes& after = sim.phaseTimes();
  BenchResult r;
  r.name = name;
  r.threads = threads;
  r.particles = sim.particleCount();
  r.blocks = sim.grid().blockCount();
  r.steps = steps;
  r.particleStepsPerSecond = double(sim.particleSteps() - ps0) / wall;
  r.binShare = (after.bin - before.bin) / wall;
  r.p2gShare = (after.p2g - before.p2g) / wall;
  r.gridShare = (after.grid - before.grid) / wall;
  r.g2pShare = (after.g2p - before.g2p) / wall;
  r.otherShare = 1 - r.binShare - r.p2gShare - r.gridShare - r.g2pShare;
  r.bytesPerParticle = double(sim.particleBytes()) / double(sim.particleCount());
  r.scratchBytesPerParticle = double(sim.scratchBytes()) / double(sim.particleCount());
  r.bytesPerBlock = double(sim.gridBytes()) / double(std::max<size_t>(1, r.blocks));
  r.secondsPerStep = wall / steps;
  return r;
}

} // namespace

BenchResult measureScaling(double particleScale, double domainScale, int steps) {
  char dx[32], lo[96], hi[96];
  std::snprintf(dx, sizeof dx, "%.6g", 0.02 / std::cbrt(particleScale));
  // The elastic case's slab; its domain ([0, 1.4] x [0, 0.9] x [0, 0.8]) grows around it.
  const double cx = 0.7, cy = 0.45;
  const double hx = 0.7 * domainScale, hy = 0.45 * domainScale, hz = 0.8 * domainScale;
  std::snprintf(lo, sizeof lo, "domain.min=[%.6g,%.6g,0]", cx - hx, cy - hy);
  std::snprintf(hi, sizeof hi, "domain.max=[%.6g,%.6g,%.6g]", cx + hx, cy + hy, hz);
  SceneSetup s = loadSceneString(substitute(kElastic, "%DX%", dx), "bench:scaling", {lo, hi});
  Simulation sim(s.settings, std::move(s.groups));
  return timeSteps("scaling", sim, int(tbb::global_control::active_value(tbb::global_control::max_allowed_parallelism)), 10, steps);
}

int runBenchmarks(const BenchOptions& opt) {
  measureBenchmarks(opt, true);
  return 0;
}

std::vector<BenchResult> measureBenchmarks(const BenchOptions& opt, bool print) {
  std::vector<BenchResult> results;
  if (print)
    std::printf("%-10s %7s %9s %7s %12s %12s %7s %7s %7s %7s %7s %8s %9s %8s\n", "case", "threads", "particles", "steps",
                "p-steps/s", "per core", "bin%", "p2g%", "grid%", "g2p%", "other%", "B/part", "scratchB", "KB/block");
  for (const std::string& name : opt.cases) {
    double oneThread = 0;
    for (int threads : opt.threads) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
      SceneSetup s = benchmarkScene(name, opt);
      Simulation sim(s.settings, std::move(s.groups));
      BenchResult r = timeSteps(name, sim, threads, benchmarkWarmup(name, opt), opt.steps);
      const double pss = r.particleStepsPerSecond;
      if (threads == 1) oneThread = pss;
      if (threads > 1 && oneThread > 0) r.efficiency = pss / (threads * oneThread);
      if (print) {
        std::printf("%-10s %7d %9zu %7d %12.3e %12.3e %7.1f %7.1f %7.1f %7.1f %7.1f %8.1f %9.1f %8.1f\n", name.c_str(),
                    threads, r.particles, opt.steps, pss, pss / threads, 100 * r.binShare, 100 * r.p2gShare,
                    100 * r.gridShare, 100 * r.g2pShare, 100 * r.otherShare, r.bytesPerParticle,
                    r.scratchBytesPerParticle, r.bytesPerBlock / 1024);
        if (r.efficiency > 0)
          std::printf("%-10s %7s parallel efficiency at %d threads: %.0f%%\n", "", "", threads, 100 * r.efficiency);
      }
      results.push_back(r);
    }
  }
  return results;
}

} // namespace talus
