// Quasi-two-dimensional granular column collapse against the run-out scaling of Lube et al.
// (2005, Phys. Rev. E 72:041301): (L_inf - L0)/L0 = 1.2 a for small aspect ratios and
// 1.9 a^(2/3) for large ones, the regime change lying at a ~ 1.8-2.8. The coefficients are
// those quoted by Lagree, Staron & Popinet (2011, JFM 686:378, eq. 3.1) for Lube's sand,
// rice and sugar. Cohesionless Drucker-Prager sand, two cells across the channel.
#include "test_support.h"

#include <gtest/gtest.h>
#include <map>

using namespace talus;

namespace {
double runOut(double aspect, double L0Cells) {
  const double dx = 0.01, L0 = L0Cells * dx, H = aspect * L0;
  const double reach = L0 * (2.5 + 2.5 * std::pow(aspect, 2.0 / 3.0));
  char buf[2048];
  std::snprintf(buf, sizeof buf, R"(
[simulation]
dx = %g
particles_per_cell = 8
end_time = 10
[domain]
min = [0, 0, 0]
max = [%g, 0.02, %g]
walls = "slip"
[terrain]
plane = { point = [0, 0, 0], normal = [0, 0, 1] }
boundary = "friction"
friction = 0.625
[[materials]]
name = "sand"
model = "drucker_prager"
density = 1500
youngs_modulus = 5e5
poisson_ratio = 0.3
friction_angle = 32
cone = "plane_strain"
[[bodies]]
material = "sand"
shape = "box"
min = [0, 0, 0]
max = [%g, 0.02, %g]
)", dx, reach, 1.1 * H, L0, H);
  auto sim = test::makeSimulation(buf);
  // Run until the deposit is at rest (the collapse lasts a few sqrt(H/g)).
  const double tEnd = 12 * std::sqrt(H / 9.81);
  sim->advanceTo(tEnd);
  EXPECT_LT(sim->maxSpeed(), 0.05 * std::sqrt(9.81 * H)) << "not at rest at a = " << aspect;
  // Front: farthest half-cell bin holding at least one layer of particles across the channel.
  const double bin = dx / 2;
  std::map<int, int> count;
  for (const auto* g : sim->groups())
    for (const Vec3& x : g->particles.x) ++count[int(std::floor(x.x() / bin))];
  double front = 0;
  for (const auto& [b, n] : count)
    if (n >= 4) front = std::max(front, (b + 1) * bin);
  return (front - L0) / L0;
}
} // namespace

TEST(ColumnCollapse, RunOutFollowsLubeScalingOnBothSidesOfTheRegimeChange) {
  const double lowA = 0.8, highA = 5.0;
  const double low = runOut(lowA, 20), lowRef = 1.2 * lowA;
  const double high = runOut(highA, 8), highRef = 1.9 * std::pow(highA, 2.0 / 3.0);
  std::printf("  a = %.1f: run-out %.3f, Lube %.3f (%+.1f%%)\n", lowA, low, lowRef, 100 * (low / lowRef - 1));
  std::printf("  a = %.1f: run-out %.3f, Lube %.3f (%+.1f%%)\n", highA, high, highRef, 100 * (high / highRef - 1));
  EXPECT_NEAR(low, lowRef, 0.2 * lowRef);
  EXPECT_NEAR(high, highRef, 0.2 * highRef);
}
