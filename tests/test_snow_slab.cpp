// A Modified Cam Clay snow slab (Table 1 snow, M = 1.2) on a 30-degree slope with a no-slip
// base, as the paper sets up its snowpacks: it rests under its own weight, and fails when a
// falling rock block (Table 1 rock) hits it. Quasi-two-dimensional, two cells across.
#include "test_support.h"

#include <gtest/gtest.h>

using namespace talus;

namespace {
constexpr double kTheta = 30 * M_PI / 180;

std::string scene(bool withRock) {
  const Vec3d n(std::sin(kTheta), 0, std::cos(kTheta)), s(std::cos(kTheta), 0, -std::sin(kTheta));
  const Vec3d p0(0, 0, 4);                      // plane point
  const Vec3d slab = p0 + 2.5 * s + 0.2 * n;    // slab centre: 5 m long, 0.4 m thick
  const Vec3d rock = p0 + 1.5 * s + 1.2 * n;    // block 0.6 m above the slab surface
  char buf[4096];
  std::snprintf(buf, sizeof buf, R"(
[simulation]
dx = 0.1
particles_per_cell = 8
end_time = 2
[domain]
min = [-0.5, 0, -0.5]
max = [6.5, 0.2, 5.5]
walls = "slip"
[terrain]
plane = { point = [%g, %g, %g], normal = [%.9g, %.9g, %.9g] }
boundary = "sticky"
[[materials]]
name = "snow"
preset = "snow"
[[materials]]
name = "rock"
preset = "rock"
[[bodies]]
material = "snow"
shape = "box"
center = [%.9g, 0.1, %.9g]
size = [5.0, 0.2, 0.4]
rotation = [0, 30, 0]
)", p0.x(), p0.y(), p0.z(), n.x(), n.y(), n.z(), slab.x(), slab.z());
  std::string out = buf;
  if (withRock) {
    std::snprintf(buf, sizeof buf, R"(
[[bodies]]
material = "rock"
shape = "box"
center = [%.9g, 0.1, %.9g]
size = [0.6, 0.2, 0.6]
rotation = [0, 30, 0]
velocity = [0, 0, -12]
)", rock.x(), rock.z());
    out += buf;
  }
  return out;
}

struct SnowState {
  double yieldedFraction, meanDownslope;
};

SnowState snowState(const Simulation& sim, const std::vector<Vec3>& x0) {
  const MaterialGroup& snow = *sim.groups()[0];
  std::vector<float> yielded;
  snow.scalar("yielded", yielded);
  double y = 0;
  for (float f : yielded) y += f;
  // Mean displacement along the slope (particles of a group keep their order between sorts
  // only by block, so compare centres of mass).
  Vec3d c = Vec3d::Zero(), c0 = Vec3d::Zero();
  for (size_t i = 0; i < snow.size(); ++i) c += snow.particles.x[i].cast<double>();
  for (const Vec3& p : x0) c0 += p.cast<double>();
  const Vec3d s(std::cos(kTheta), 0, -std::sin(kTheta));
  return {y / double(snow.size()), (c / double(snow.size()) - c0 / double(x0.size())).dot(s)};
}
} // namespace

TEST(SnowSlab, RestsOnThirtyDegreesAndFailsUnderARockImpact) {
  auto quiet = test::makeSimulation(scene(false));
  const auto x0 = quiet->groups()[0]->particles.x;
  quiet->advanceTo(1.0);
  const SnowState still = snowState(*quiet, x0);
  std::printf("  without rock: yielded %.3f, downslope %.2e m\n", still.yieldedFraction, still.meanDownslope);
  EXPECT_EQ(still.yieldedFraction, 0.0);               // elastic: 1.2 kPa load against p0 = 175 kPa
  EXPECT_LT(std::abs(still.meanDownslope), 2e-3);      // only elastic settling

  auto hit = test::makeSimulation(scene(true));
  const auto y0 = hit->groups()[0]->particles.x;
  hit->advanceTo(1.0);
  const SnowState failed = snowState(*hit, y0);
  std::printf("  with rock:    yielded %.3f, downslope %.2e m\n", failed.yieldedFraction, failed.meanDownslope);
  EXPECT_GT(failed.yieldedFraction, 0.2);
  EXPECT_GT(failed.meanDownslope, 0.05);
}
