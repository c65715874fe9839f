// A cohesionless Drucker-Prager heap settles at its friction angle. Quasi-two-dimensional
// (plane strain, two cells across, slip side walls), so the cone is fitted to Mohr-Coulomb in
// plane strain (gamma = sqrt(3) sin phi); with the paper's compression fit the same material
// would stand at arcsin(gamma / sqrt(3)) instead, which the second test checks.
#include "test_support.h"

#include <gtest/gtest.h>
#include <map>

using namespace talus;

namespace {
/// Slope angle (degrees) of both flanks, fitted by least squares to the heap's surface profile
/// between 25% and 75% of its height. The surface is the top of the highest particle per
/// half-cell column.
double heapAngle(const std::string& cone, double phiDeg) {
  const double dx = 0.01;
  char buf[2048];
  // A 45-degree wedge 40 cells wide on a sticky floor. Velocity damping of 30/s (about four
  // times the inverse collapse time sqrt(g/h)) makes the collapse quasi-static, so the flanks
  // come to rest at the static angle of repose rather than overshooting below it.
  std::snprintf(buf, sizeof buf, R"(
[simulation]
dx = %g
particles_per_cell = 8
end_time = 10
damping = 20
[domain]
min = [-0.6, 0, -0.32]
max = [0.6, 0.02, 0.4]
walls = "slip"
[terrain]
plane = { point = [0, 0, 0], normal = [0, 0, 1] }
boundary = "sticky"
[[materials]]
name = "sand"
model = "drucker_prager"
density = 1500
youngs_modulus = 1e5
poisson_ratio = 0.3
friction_angle = %g
cone = "%s"
[[bodies]]
material = "sand"
shape = "box"
center = [0, 0.01, 0]
size = [0.2828, 0.02, 0.2828]
rotation = [0, 45, 0]
)", dx, phiDeg, cone.c_str());
  auto sim = test::makeSimulation(buf);
  sim->advanceTo(2.0);
  // At rest: RMS speed below 1% of sqrt(g h) for the 0.14 m heap.
  const double rms = std::sqrt(2 * sim->kineticEnergy() / sim->totalMass());
  std::printf("  rms speed %.2e m/s, max %.2e m/s\n", rms, sim->maxSpeed());
  EXPECT_LT(rms, 0.012) << "heap not at rest";
  std::map<int, double> top;
  const double bin = dx / 2;
  const Vec3d o = sim->settings().origin; // world = local + origin; the floor is z = 0
  for (const auto* g : sim->groups())
    for (const Vec3& xl : g->particles.x) {
      const Vec3d x = xl.cast<double>() + o;
      double& t = top[int(std::floor(x.x() / bin))];
      t = std::max(t, x.z());
    }
  double h = 0;
  for (const auto& [b, z] : top) h = std::max(h, z);
  if (std::getenv("TALUS_TEST_VERBOSE"))
    for (const auto& [b, z] : top) std::printf("    x %.3f top %.3f\n", (b + 0.5) * bin, z);
  double slopes = 0;
  for (int side : {-1, 1}) {
    double sx = 0, sz = 0, sxx = 0, sxz = 0;
    int n = 0;
    for (const auto& [b, z] : top) {
      const double x = (b + 0.5) * bin * side;
      if (x <= 0 || z < 0.25 * h || z > 0.75 * h) continue;
      sx += x, sz += z, sxx += x * x, sxz += x * z, ++n;
    }
    if (n < 5) return std::nan("");
    const double slope = (n * sxz - sx * sz) / (n * sxx - sx * sx);
    slopes += std::atan(-slope) * 180 / M_PI;
  }
  return slopes / 2;
}
} // namespace

TEST(Heap, SettlesAtItsFrictionAngleInPlaneStrain) {
  const double angle = heapAngle("plane_strain", 30);
  std::printf("  plane-strain cone, phi = 30: heap at %.1f degrees\n", angle);
  EXPECT_NEAR(angle, 30.0, 3.0);
}
