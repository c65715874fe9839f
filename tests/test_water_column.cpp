// A 10 m water column at rest: hydrostatic pressure, and stiff water (B = 3e8 Pa) staying still.
#include "test_support.h"

#include <algorithm>
#include <gtest/gtest.h>
#include <map>

using namespace talus;

namespace {
std::string column(const std::string& water) {
  return R"(
[simulation]
dx = 0.5
particles_per_cell = 8
end_time = 10
[domain]
min = [0, 0, 0]
max = [2, 2, 12]
walls = "slip"
[[materials]]
name = "water"
)" + water + R"(
[[bodies]]
material = "water"
shape = "box"
min = [0, 0, 0]
max = [2, 2, 10]
)";
}

/// Worst error of the mean particle pressure against the weight of the water above, over 1 m
/// depth bins from 1 m to 9 m. The weight above a particle is counted in its column of the
/// initial lattice (spacing dx/2 at 8 particles per cell): rho0 g s (n_above + 1/2). Depth is
/// measured by mass, not geometry, because the no-tension clamp lets the top layer dilate by
/// ~0.2 dx, which shifts the geometric surface but not the weight. `wallBin` gets the bottom bin.
double worstHydrostaticError(const Simulation& sim, double* wallBin = nullptr) {
  const MaterialGroup& g = *sim.groups()[0];
  std::vector<float> p;
  g.scalar("pressure", p);
  const double s = 0.25;
  auto column = [&](size_t i) {
    return std::make_pair(int(std::floor(g.particles.x[i].x() / s)), int(std::floor(g.particles.x[i].y() / s)));
  };
  std::map<std::pair<int, int>, std::vector<double>> columns;
  for (size_t i = 0; i < g.size(); ++i) columns[column(i)].push_back(g.particles.x[i].z());
  for (auto& [k, zs] : columns) std::sort(zs.begin(), zs.end());
  std::vector<double> sum(10, 0), ref(10, 0);
  for (size_t i = 0; i < g.size(); ++i) {
    const auto& zs = columns[column(i)];
    const size_t above = size_t(zs.end() - std::upper_bound(zs.begin(), zs.end(), double(g.particles.x[i].z())));
    const double depth = s * (double(above) + 0.5);
    const int bin = std::min(9, int(depth));
    sum[bin] += p[i], ref[bin] += 1000 * 9.81 * depth;
  }
  double worst = 0;
  for (int b = 1; b < 9; ++b) worst = std::max(worst, std::abs(sum[b] / ref[b] - 1));
  if (wallBin) *wallBin = sum[9] / ref[9] - 1;
  return worst;
}
} // namespace

TEST(WaterColumn, ReachesHydrostaticPressureUnderSlowlyRampedGravity) {
  // Softened water (c = 50 m/s), starting unpressurised; gravity ramped over 6 s, about eight
  // acoustic periods 4H/c = 0.8 s, so the column is loaded quasi-statically.
  auto sim = test::makeSimulation(column("model = \"water\"\ndensity = 1000\nsound_speed = 50\nhydrostatic = false"),
                                  {"simulation.gravity_ramp=6.0"});
  sim->advanceTo(7.0);
  double wall = 0;
  const double err = worstHydrostaticError(*sim, &wall);
  std::printf("  worst interior depth-bin error: %.2f%%; bin at the bottom wall: %+.2f%%\n", 100 * err, 100 * wall);
  EXPECT_LT(err, 0.02);
}

TEST(WaterColumn, StiffWaterStartedHydrostaticStaysStillForTwoSeconds) {
  auto sim = test::makeSimulation(column("preset = \"water\""));
  ASSERT_NEAR(sim->maxWaveSpeed(), 1449.1, 0.5);
  EXPECT_LT(worstHydrostaticError(*sim), 0.02);
  const double limit = 1e-3 * std::sqrt(9.81 * 10);
  double worst = 0;
  while (sim->time() < 2.0) {
    sim->step(2.0 - sim->time());
    worst = std::max(worst, sim->maxSpeed());
  }
  std::printf("  max speed over 2 s: %.2e m/s (limit %.2e), %llu steps\n", worst, limit,
              (unsigned long long)sim->steps());
  EXPECT_LT(worst, limit);
  EXPECT_LT(worstHydrostaticError(*sim), 0.02);
}
