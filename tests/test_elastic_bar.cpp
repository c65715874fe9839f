// First longitudinal mode of a fixed-free elastic bar: period T = 4 L / c, c = sqrt(E / rho).
#include "test_support.h"

#include <cmath>
#include <gtest/gtest.h>

using namespace talus;

TEST(ElasticBar, FirstModePeriodWithinTwoPercentOfFourLOverC) {
  // nu = 0 makes the bar speed sqrt(E/rho) equal the P-wave speed, so lateral inertia and
  // confinement cannot blur the comparison. 32 cells along the bar.
  const double L = 1.0, E = 1e5, rho = 1000, c = std::sqrt(E / rho), T = 4 * L / c; // T = 0.4 s
  auto sim = test::makeSimulation(R"(
[simulation]
dx = 0.03125
end_time = 1.0
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
min = [0, -0.0625, -0.0625]
max = [1.0, 0.0625, 0.0625]
)");
  // Excite the first mode: v(x) = v0 sin(pi x / 2L). Small amplitude keeps strains ~1e-3.
  for (auto* g : sim->groups())
    for (size_t i = 0; i < g->size(); ++i)
      g->particles.v[i] = Vec3(Real(0.01 * std::sin(M_PI * g->particles.x[i].x() / (2 * L))), 0, 0);

  // The mean velocity goes as cos(2 pi t / T): find its zero crossings.
  std::vector<double> crossings;
  double prevT = 0, prevV = test::meanVelocity(*sim).x();
  while (sim->time() < 2.2 * T) {
    sim->step();
    const double v = test::meanVelocity(*sim).x();
    if ((prevV > 0) != (v > 0)) crossings.push_back(prevT + (sim->time() - prevT) * prevV / (prevV - v));
    prevT = sim->time(), prevV = v;
  }
  ASSERT_GE(crossings.size(), 4u);
  const double measured = 0.5 * (crossings[3] - crossings[1]) + 0.5 * (crossings[2] - crossings[0]);
  std::printf("  period %.5f s, 4L/c = %.5f s, error %+.2f%%\n", measured, T, 100 * (measured / T - 1));
  EXPECT_NEAR(measured, T, 0.02 * T) << "measured period " << measured << " s, expected " << T << " s";
}
