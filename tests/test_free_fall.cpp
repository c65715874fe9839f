// A stress-free body in free fall follows x = x0 + g t^2 / 2.
#include "test_support.h"

#include <gtest/gtest.h>

using namespace talus;

TEST(FreeFall, CentreOfMassFollowsHalfGTSquared) {
  auto sim = test::makeSimulation(R"(
[simulation]
dx = 0.05
end_time = 0.5
gravity = [0, 0, -9.81]
max_dt = 0.002
[domain]
min = [0, 0, 0]
max = [1, 1, 3]
[[materials]]
name = "ball"
model = "elastic"
density = 1000
youngs_modulus = 1e5
[[bodies]]
material = "ball"
shape = "sphere"
center = [0.5, 0.5, 2.5]
radius = 0.15
)");
  const Vec3d c0 = test::centreOfMass(*sim);
  double maxDt = 0;
  while (sim->time() < 0.5) maxDt = std::max(maxDt, sim->step(0.5 - sim->time()));
  const double t = sim->time();
  const double drop = c0.z() - test::centreOfMass(*sim).z();
  const double exact = 0.5 * 9.81 * t * t;
  // Symplectic Euler moves each step with the end-of-step velocity: the position leads the
  // exact parabola by at most g t dt / 2, a first-order error bounded here by the largest step.
  EXPECT_NEAR(drop, exact, 0.5 * 9.81 * t * maxDt + 1e-6);
  EXPECT_NEAR(test::meanVelocity(*sim).z(), -9.81 * t, 1e-4 * 9.81 * t);
  EXPECT_NEAR(test::meanVelocity(*sim).x(), 0.0, 1e-6);
  EXPECT_GT(drop, 1.0); // fell more than a metre: far beyond the tolerance
}
