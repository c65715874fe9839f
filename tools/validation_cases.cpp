#include "tools/validation_cases.h"
#include "tools/validation_support.h"

#include "engine/simulation.h"
#include "io/scene/scene.h"

#include <algorithm>
#include <chrono>
#include <cstdarg>
#include <cstdio>
#include <cmath>
#include <fstream>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>

namespace talus::validation {

namespace {

using namespace detail;

double meanVelocityX(const Simulation& sim) { return sim.meanVelocity().x(); }

} // namespace

double SlidingBlockResult::maxRelErrorBeyond(double distance) const {
  double e = 0;
  for (size_t i = 0; i < t.size(); ++i)
    if (exact[i] > distance) e = std::max(e, std::abs(s[i] / exact[i] - 1));
  return e;
}

SlidingBlockResult slidingBlock(double mu, const Resolution& r, double endTime, double gravityRamp) {
  constexpr double kTheta = 30.0 * M_PI / 180.0, kAzimuth = 20.0 * M_PI / 180.0, kG = 9.81;
  const double dx = 0.2 / r.cells;
  const Vec3d n(std::sin(kTheta) * std::cos(kAzimuth), std::sin(kTheta) * std::sin(kAzimuth), std::cos(kTheta));
  const Vec3d s(std::cos(kTheta) * std::cos(kAzimuth), std::cos(kTheta) * std::sin(kAzimuth), -std::sin(kTheta));
  const Vec3d p0(0.6, 0.6, 1.4), c = p0 + 0.1 * n; // bottom face on the plane
  const std::string toml = format(R"(
[simulation]
dx = %.9g
end_time = 10
gravity = [0, 0, -9.81]
gravity_ramp = %.9g
[domain]
min = [0, 0, 0]
max = [2.2, 1.6, 1.8]
walls = "slip"
[terrain]
plane = { point = [%.9g, %.9g, %.9g], normal = [%.9g, %.9g, %.9g] }
boundary = "friction"
friction = %.9g
[[materials]]
name = "block"
model = "elastic"
density = 1000
youngs_modulus = 1e6
poisson_ratio = 0.3
[[bodies]]
material = "block"
shape = "box"
center = [%.9g, %.9g, %.9g]
size = [0.4, 0.3, 0.2]
rotation = [0, 30, 20]
)", dx, gravityRamp, p0.x(), p0.y(), p0.z(), n.x(), n.y(), n.z(), mu, c.x(), c.y(), c.z());
  SlidingBlockResult res;
  auto sim = build(toml, r, res);
  const auto t0 = Clock::now();
  const Vec3d c0 = sim->centreOfMass();
  const double a = kG * (std::sin(kTheta) - mu * std::cos(kTheta)), T = gravityRamp;
  // Under the engine's cosine ramp g (1 - cos(pi t / T)) / 2 a sliding block's acceleration is
  // a times the ramp (both gravity's components scale), integrated twice.
  auto exactAt = [&](double t) {
    if (a <= 0) return 0.0;
    if (T <= 0) return 0.5 * a * t * t;
    if (t <= T) return a * (t * t / 4 + T * T / (2 * M_PI * M_PI) * (std::cos(M_PI * t / T) - 1));
    return a * (T * T / 4 - T * T / (M_PI * M_PI) + T / 2 * (t - T) + 0.5 * (t - T) * (t - T));
  };
  for (int i = 1; i * 0.05 <= endTime + 1e-9; ++i) {
    const double t = i * 0.05;
    sim->advanceTo(t);
    const double disp = (sim->centreOfMass() - c0).dot(s), exact = exactAt(t);
    res.t.push_back(t), res.s.push_back(disp), res.exact.push_back(exact);
    res.restDisplacement = std::abs(disp);
  }
  double p2 = 0, m = 0;
  for (const auto* g : sim->groups())
    for (size_t i = 0; i < g->size(); ++i) {
      p2 += double(g->particles.mass[i]) * double(g->particles.v[i].squaredNorm());
      m += double(g->particles.mass[i]);
    }
  res.restSpeed = std::sqrt(p2 / m);
  finish(*sim, t0, res);
  return res;
}

ElasticBarResult elasticBar(const Resolution& r) {
  const double L = 1.0, E = 1e5, rho = 1000;
  const double dx = L / r.cells, half = std::max(0.0625, 0.5 * dx); // cross-section at least one cell
  const std::string toml = format(R"(
[simulation]
dx = %.9g
end_time = 10
gravity = [0, 0, 0]
[domain]
min = [0, -0.5, -0.5]
max = [1.5, 0.5, 0.5]
walls = "sticky"
[[materials]]
name = "bar"
model = "elastic"
density = 1000
youngs_modulus = 1e5
poisson_ratio = 0.0
[[bodies]]
material = "bar"
shape = "box"
min = [0, %.9g, %.9g]
max = [1.0, %.9g, %.9g]
)", dx, -half, -half, half, half);
  ElasticBarResult res;
  auto sim = build(toml, r, res);
  const auto t0 = Clock::now();
  // First mode, v(x) = v0 sin(pi x / 2L); small amplitude keeps strains ~1e-3.
  for (auto* g : sim->groups())
    for (size_t i = 0; i < g->size(); ++i)
      g->particles.v[i] = Vec3(Real(0.01 * std::sin(M_PI * g->particles.x[i].x() / (2 * L))), 0, 0);
  res.exact = 4 * L / std::sqrt(E / rho);
  std::vector<double> crossings;
  double prevT = 0, prevV = meanVelocityX(*sim);
  while (sim->time() < 2.2 * res.exact) {
    sim->step();
    const double v = meanVelocityX(*sim);
    if ((prevV > 0) != (v > 0)) crossings.push_back(prevT + (sim->time() - prevT) * prevV / (prevV - v));
    prevT = sim->time(), prevV = v;
  }
  if (crossings.size() < 4) throw std::runtime_error("elastic bar: fewer than four zero crossings");
  res.period = 0.5 * (crossings[3] - crossings[1]) + 0.5 * (crossings[2] - crossings[0]);
  res.relError = res.period / res.exact - 1;
  finish(*sim, t0, res);
  return res;
}

ColumnCollapseResult columnCollapse(double aspect, const Resolution& r, GranularModel model) {
  const double L0 = 0.2, dx = L0 / r.cells, H = aspect * L0;
  const double bed = r.bedOffset * dx; // 0: the bed on a node plane, as the tables are
  const double reach = L0 * (2.5 + 2.5 * std::pow(aspect, 2.0 / 3.0));
  const char* material = model == GranularModel::MuI ? R"(model = "mu_i"
mu_s = 0.6249
mu_2 = 0.9657
i0 = 0.279
grain_diameter = 0.001
grain_density = 2500)"
                                                     : R"(model = "drucker_prager"
friction_angle = 32
cone = "plane_strain")";
  const std::string toml = format(R"(
[simulation]
dx = %.9g
end_time = 100
[domain]
min = [0, 0, 0]
max = [%.9g, %.9g, %.9g]
walls = "slip"
[terrain]
plane = { point = [0, 0, %.9g], normal = [0, 0, 1] }
boundary = "friction"
friction = 0.625
[[materials]]
name = "sand"
density = 1500
youngs_modulus = 5e5
poisson_ratio = 0.3
%s
[[bodies]]
material = "sand"
shape = "box"
min = [0, 0, %.9g]
max = [%.9g, %.9g, %.9g]
)", dx, reach, 2 * dx, 1.1 * H + bed, bed, material, bed, L0, 2 * dx, bed + H);
  ColumnCollapseResult res;
  auto sim = build(toml, r, res);
  const auto t0 = Clock::now();
  sim->advanceTo(12 * std::sqrt(H / 9.81)); // the collapse lasts a few sqrt(H/g)
  // Front: deposit at least 0.025 L0 thick (one particle spacing at 20 cells across L0).
  const double spacing = dx / std::cbrt(double(r.particlesPerCell));
  res.runOut = (contiguousFront(*sim, spacing, 2 * dx, 0.025 * L0) - L0) / L0;
  res.runOutAcrossCell = (contiguousFront(*sim, spacing, 2 * dx, 0.025 * L0, dx) - L0) / L0;
  // 0.025 L0 is one particle layer (the spacing) at 20 cells: below that one layer counts, above
  // it two are needed. Half a layer at every dx counts the same deposit at every resolution.
  res.runOutAnyLayer = (contiguousFront(*sim, spacing, 2 * dx, 0.5 * spacing) - L0) / L0;
  const double small = 1.2 * aspect, large = 1.9 * std::pow(aspect, 2.0 / 3.0);
  res.lubeLow = aspect <= 2.8 ? small : large, res.lubeHigh = aspect < 1.8 ? small : large;
  if (res.lubeLow > res.lubeHigh) std::swap(res.lubeLow, res.lubeHigh);
  res.reference = 0.5 * (res.lubeLow + res.lubeHigh);
  res.lajeunesse = std::min(1.8 * aspect, 2.3 * std::pow(aspect, 2.0 / 3.0));
  res.relError = res.runOut < res.lubeLow ? res.runOut / res.lubeLow - 1
                 : res.runOut > res.lubeHigh ? res.runOut / res.lubeHigh - 1 : 0.0;
  // Height: the thickest bin one cell wide; farthest: the farthest particle.
  const double ox = sim->settings().origin.x();
  std::map<int, double> volume;
  std::vector<std::pair<double, double>> byX; // (x, volume) per particle
  double xMax = 0, total = 0;
  for (const auto* g : sim->groups())
    for (size_t i = 0; i < g->size(); ++i) {
      const double x = double(g->particles.x[i].x()) + ox, v = double(g->particles.mass[i]) / g->density();
      volume[int(std::floor(x / dx))] += v;
      byX.push_back({x, v});
      total += v;
      xMax = std::max(xMax, x);
    }
  std::sort(byX.begin(), byX.end());
  double behind = 0;
  for (const auto& [x, v] : byX)
    if ((behind += v) >= 0.99 * total) {
      res.runOut99 = (x - L0) / L0;
      break;
    }
  for (const auto& [b, v] : volume) res.finalHeight = std::max(res.finalHeight, v / (dx * 2 * dx) / L0);
  res.referenceHeight = aspect <= 1.15 ? aspect : std::pow(aspect, 0.4);
  res.farthest = (xMax - L0) / L0;
  res.finalRmsSpeed = std::sqrt(2 * sim->kineticEnergy() / sim->totalMass());
  res.collapseSpeedScale = std::sqrt(9.81 * H);
  finish(*sim, t0, res);
  return res;
}

std::string thinLayerScene(double layerSide, double domainSide, double domainHeight) {
  char buf[1024];
  std::snprintf(buf, sizeof buf, R"(
[simulation]
dx = 5.0
particles_per_cell = 1
end_time = 1.0
[domain]
min = [0, 0, 0]
max = [%g, %g, %g]
[[materials]]
name = "snowlike"
model = "elastic"
density = 300
youngs_modulus = 1e6
[[bodies]]
material = "snowlike"
shape = "box"
min = [0, 0, 500]
max = [%g, %g, 505]
)", domainSide, domainSide, domainHeight, layerSide, layerSide);
  return buf;
}

} // namespace talus::validation
