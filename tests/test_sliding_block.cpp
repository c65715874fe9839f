// A block on a 30-degree plane turned 20 degrees off the grid axes, Coulomb friction through
// the terrain SDF: s(t) = g t^2 (sin(theta) - mu cos(theta)) / 2 when tan(theta) > mu, else rest.
#include "test_support.h"

#include <cmath>
#include <gtest/gtest.h>

using namespace talus;

namespace {
constexpr double kTheta = 30.0 * M_PI / 180.0, kAzimuth = 20.0 * M_PI / 180.0, kG = 9.81, kDx = 0.05;

std::string scene(double mu) {
  const Vec3d n(std::sin(kTheta) * std::cos(kAzimuth), std::sin(kTheta) * std::sin(kAzimuth), std::cos(kTheta));
  const Vec3d p0(0.6, 0.6, 1.4);      // a point of the plane
  const Vec3d c = p0 + 0.1 * n;       // block centre: bottom face on the plane
  char buf[2048];
  std::snprintf(buf, sizeof buf, R"(
[simulation]
dx = %g
end_time = 1.0
gravity = [0, 0, -9.81]
[domain]
min = [0, 0, 0]
max = [2.2, 1.6, 1.8]
walls = "slip"
[terrain]
plane = { point = [%.9g, %.9g, %.9g], normal = [%.9g, %.9g, %.9g] }
boundary = "friction"
friction = %g
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
)", kDx, p0.x(), p0.y(), p0.z(), n.x(), n.y(), n.z(), mu, c.x(), c.y(), c.z());
  return buf;
}

Vec3d downhill() {
  return {std::cos(kTheta) * std::cos(kAzimuth), std::cos(kTheta) * std::sin(kAzimuth), -std::sin(kTheta)};
}
} // namespace

TEST(SlidingBlock, CoulombSlidingMatchesAnalyticWithinTwoPercent) {
  const double mu = 0.3, a = kG * (std::sin(kTheta) - mu * std::cos(kTheta)); // 2.356 m/s^2
  auto sim = test::makeSimulation(scene(mu));
  const Vec3d c0 = test::centreOfMass(*sim);
  int checked = 0;
  for (double t = 0.05; t <= 0.9001; t += 0.05) {
    sim->advanceTo(t);
    const double s = (test::centreOfMass(*sim) - c0).dot(downhill());
    const double exact = 0.5 * a * t * t;
    if (exact > 5 * kDx) {
      EXPECT_NEAR(s, exact, 0.02 * exact) << "t = " << t;
      std::printf("  t = %.2f s  s = %.4f m  exact %.4f m  error %+.2f%%\n", t, s, exact, 100 * (s / exact - 1));
      ++checked;
    }
  }
  EXPECT_GE(checked, 5);
}

TEST(SlidingBlock, StaysAtRestWhenFrictionExceedsTheSlope) {
  // tan(30) = 0.577 < 0.7. An unstressed elastic block loaded suddenly rings with the normal
  // force swinging between 0 and twice its static value (nothing damps it), and it slips
  // whenever N < 0.82 N_static, as a real undamped block would. Ramping gravity over 0.2 s
  // (about ten periods of the block's normal mode) loads it quasi-statically instead.
  auto sim = test::makeSimulation(scene(0.7), {"simulation.gravity_ramp=0.2"});
  const Vec3d c0 = test::centreOfMass(*sim);
  sim->advanceTo(0.7);
  const double s = (test::centreOfMass(*sim) - c0).dot(downhill());
  // Sliding at 2.356 m/s^2 (had mu been 0.3) would have moved ~0.45 m; the elastic shear
  // settling of a 0.2 m block is rho g h sin(theta) h / G ~ 0.5 mm.
  EXPECT_LT(std::abs(s), 0.05 * kDx);
  EXPECT_LT(test::meanVelocity(*sim).norm(), 5e-3);
}

TEST(SlidingBlock, SlipsWithTheSameRampWhenFrictionIsLow) {
  // Control for the test above: the ramp alone does not hold the block.
  auto sim = test::makeSimulation(scene(0.3), {"simulation.gravity_ramp=0.2"});
  const Vec3d c0 = test::centreOfMass(*sim);
  sim->advanceTo(0.7);
  EXPECT_GT((test::centreOfMass(*sim) - c0).dot(downhill()), 4 * kDx);
}
