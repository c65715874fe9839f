// Secondary releases (engine/secondary_release.h, `trigger_thickness` on a body): a slab sliding
// down a 30-degree bed (Coulomb 0.2) reaches a held body downstream; the body joins the run when
// the flow over it weighs as much per area as `trigger_thickness` of its material, which for a
// 0.1 m slab of the same material and a 0.05 m trigger is when the slab's front reaches the body's
// upstream edge (half the nearest node column's kernel covered).
#include "engine/secondary_release.h"
#include "test_support.h"

#include <cmath>
#include <gtest/gtest.h>

using namespace talus;

namespace {

constexpr double kG = 9.81, kTheta = 30 * M_PI / 180, kMu = 0.2, kDx = 0.05, kRamp = 0.1;

std::string scene(const std::string& trigger) {
  char buf[1400];
  std::snprintf(buf, sizeof buf, R"(
[simulation]
dx = %g
end_time = 10
gravity = [%.12g, 0, %.12g]
gravity_ramp = %g
[domain]
min = [0, 0, -0.2]
max = [3.2, 0.4, 0.4]
walls = "slip"
[terrain]
plane = { point = [0, 0, 0], normal = [0, 0, 1] }
boundary = "friction"
friction = %g
[[materials]]
name = "snow"
model = "elastic"
density = 300
youngs_modulus = 1e6
[[bodies]]
name = "slab"
material = "snow"
shape = "box"
min = [0.1, 0.05, 0]
max = [0.4, 0.35, 0.1]
[[bodies]]
name = "held"
material = "snow"
shape = "box"
min = [1.4, 0.05, 0]
max = [1.7, 0.35, 0.1]
%s
)",
                kDx, kG * std::sin(kTheta), -kG * std::cos(kTheta), kRamp, kMu, trigger.c_str());
  return buf;
}

/// When the slab's front (x = 0.4 at rest) reaches `x` under the ramped gravity: RK4.
double arrival(double x) {
  double front = 0.4, v = 0, t = 0;
  const double h = 1e-5;
  auto acc = [](double tt) {
    const double s = tt >= kRamp ? 1.0 : 0.5 * (1 - std::cos(M_PI * tt / kRamp));
    return s * kG * (std::sin(kTheta) - kMu * std::cos(kTheta));
  };
  while (front < x) {
    const double a1 = acc(t), a2 = acc(t + h / 2), a4 = acc(t + h);
    front += h * (v + h / 6 * (a1 + 2 * a2));
    v += h / 6 * (a1 + 4 * a2 + a4);
    t += h;
  }
  return t;
}

const SecondaryReleases* held(const Simulation& sim) {
  for (const auto& s : sim.sources())
    if (auto* h = dynamic_cast<const SecondaryReleases*>(s.get())) return h;
  return nullptr;
}

} // namespace

TEST(SecondaryRelease, AHeldBodyJoinsWhenTheFlowReachesIt) {
  auto sim = test::makeSimulation(scene("trigger_thickness = 0.05"));
  ASSERT_NE(held(*sim), nullptr);
  const size_t slab = sim->groups()[0]->size();
  const size_t heldCount = held(*sim)->bodies()[0].x.size();
  EXPECT_EQ(heldCount, slab) << "the same box, held";
  const double massBefore = sim->totalMass();
  while (std::isnan(held(*sim)->releaseTime(0)) && sim->time() < 2.0) sim->step();
  const double t = held(*sim)->releaseTime(0);
  const double expected = arrival(1.4), early = arrival(1.4 - kDx), late = arrival(1.4 + kDx);
  std::printf("  released at %.4f s; the slab's front reaches the body's edge at %.4f s (one cell either side: "
              "%.4f .. %.4f s)\n", t, expected, early, late);
  // One cell of travel either side: the grid spreads the slab's mass a cell beyond its front (as
  // tests/test_terrain_regions.cpp measures), and the node columns are a cell apart.
  EXPECT_GT(t, early);
  EXPECT_LT(t, late);
  EXPECT_EQ(sim->groups()[0]->size(), slab + heldCount);
  EXPECT_NEAR(sim->totalMass(), 2 * massBefore, 1e-6 * massBefore) << "the held body's mass joins";
  // Released at rest, where it was seeded.
  const auto& P = sim->groups()[0]->particles;
  const auto& H = held(*sim)->bodies()[0];
  for (size_t p = slab; p < P.size(); ++p) {
    EXPECT_EQ(P.v[p].norm(), 0.0f);
    EXPECT_EQ(P.x[p], H.x[p - slab]);
  }
}

TEST(SecondaryRelease, WithoutATriggerTheBodyIsSeededAsAnyOtherAndABadTriggerIsOneLine) {
  auto sim = test::makeSimulation(scene(""));
  EXPECT_EQ(held(*sim), nullptr);
  try {
    test::makeSimulation(scene("trigger_thickness = -1"));
    ADD_FAILURE() << "a negative trigger was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("trigger_thickness"), std::string::npos) << e.what();
  }
}
