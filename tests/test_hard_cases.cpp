// Violent cases at coarse resolution: the run must stay finite, must not gain energy (kinetic +
// gravitational never rises above its initial value by more than 2% of the energy in play:
// nothing here does work on the system, plasticity and friction only take energy out), and must
// account for all mass (in the domain + removed = initial, exactly up to summation rounding).
#include "test_support.h"

#include <gtest/gtest.h>

using namespace talus;

namespace {
struct HardCaseResult {
  double energyGrowth; ///< max over steps of (E - E0) / E_scale
  double maxSpeed;
  uint64_t steps;
  double massRemoved;
};

HardCaseResult runHardCase(const std::string& toml, double duration) {
  auto sim = test::makeSimulation(toml);
  const double m0 = sim->totalMass();
  double zMin = 1e300;
  for (const auto* g : sim->groups())
    for (const Vec3& x : g->particles.x) zMin = std::min(zMin, double(x.z()));
  const double g = sim->settings().gravity.norm();
  double scale = sim->kineticEnergy();
  for (const auto* grp : sim->groups())
    for (size_t i = 0; i < grp->size(); ++i)
      scale += double(grp->particles.mass[i]) * g * (double(grp->particles.x[i].z()) - zMin);
  const double e0 = sim->kineticEnergy() + sim->potentialEnergy();
  HardCaseResult r{0, 0, 0, 0};
  double lastRemoved = 0, removedEnergy = 0;
  while (sim->time() < duration) {
    sim->step(duration - sim->time()); // NumericalError would propagate and fail the test
    // Energy carried out of the domain by removed particles is not "growth": add it back,
    // bounded by the largest energy a removed particle could have carried (speed * mass).
    if (sim->totalMassRemoved() > lastRemoved) {
      removedEnergy += (sim->totalMassRemoved() - lastRemoved) * (0.5 * sim->maxSpeed() * sim->maxSpeed() + g * 10);
      lastRemoved = sim->totalMassRemoved();
    }
    const double e = sim->kineticEnergy() + sim->potentialEnergy();
    r.energyGrowth = std::max(r.energyGrowth, (e - e0 - removedEnergy) / scale);
    r.maxSpeed = std::max(r.maxSpeed, sim->maxSpeed());
  }
  r.steps = sim->steps();
  r.massRemoved = sim->totalMassRemoved();
  EXPECT_NEAR(sim->totalMass() + sim->totalMassRemoved(), m0, 1e-9 * m0) << "mass not accounted for";
  for (const auto* grp : sim->groups())
    for (size_t i = 0; i < grp->size(); ++i) {
      EXPECT_TRUE(grp->particles.x[i].allFinite());
      EXPECT_TRUE(grp->particles.tau[i].matrix().allFinite());
    }
  return r;
}

void expectStable(const HardCaseResult& r, const char* what) {
  std::printf("  %s: %llu steps, max speed %.1f m/s, energy growth %.2e of the energy in play\n", what,
              (unsigned long long)r.steps, r.maxSpeed, r.energyGrowth);
  EXPECT_LT(r.energyGrowth, 0.02) << what;
}

std::string impactScene(const std::string& targetMaterial, const std::string& target) {
  return R"(
[simulation]
dx = 0.1
end_time = 1
[domain]
min = [0, 0, 0]
max = [3, 1, 2.5]
walls = "slip"
[[materials]]
name = "rock"
preset = "rock"
[[materials]]
name = "target"
)" + targetMaterial + R"(
[[bodies]]
material = "target"
shape = "box"
)" + target + R"(
[[bodies]]
material = "rock"
shape = "box"
center = [1.5, 0.5, 1.2]
size = [0.4, 0.4, 0.4]
velocity = [20, 0, -46]
)";
}
} // namespace

TEST(HardCases, RockBlockHitsWaterAtFiftyMetresPerSecond) {
  // Water softened to c = 500 m/s, ten times the impact speed (density error ~1%).
  expectStable(runHardCase(impactScene("model = \"water\"\ndensity = 1000\nsound_speed = 500",
                                       "min = [0, 0, 0]\nmax = [3, 1, 0.8]"),
                           0.15),
               "rock into water at 50 m/s");
}

TEST(HardCases, RockBlockHitsIceAndSnowLayersAtFiftyMetresPerSecond) {
  expectStable(runHardCase(impactScene("preset = \"ice\"", "min = [0, 0, 0]\nmax = [3, 1, 0.6]"), 0.2),
               "rock into ice at 50 m/s");
  expectStable(runHardCase(impactScene("preset = \"snow\"", "min = [0, 0, 0]\nmax = [3, 1, 0.6]"), 0.2),
               "rock into snow at 50 m/s");
}

TEST(HardCases, ThinSnowLayerOnAFiftyDegreeSlope) {
  // One to two cells of snow on a 50-degree frictional slope: it slides off as a sheet.
  const double th = 50 * M_PI / 180;
  char buf[2048];
  std::snprintf(buf, sizeof buf, R"(
[simulation]
dx = 0.1
end_time = 1
[domain]
min = [0, 0, 0]
max = [4, 0.4, 4]
walls = "open"
[terrain]
plane = { point = [0, 0, 3.5], normal = [%.9g, 0, %.9g] }
boundary = "friction"
friction = 0.3
[[materials]]
name = "snow"
preset = "snow"
[[bodies]]
material = "snow"
shape = "box"
center = [%.9g, 0.2, %.9g]
size = [2.0, 0.4, 0.15]
rotation = [0, 50, 0]
)", std::sin(th), std::cos(th), 1.0 * std::cos(th) + 0.075 * std::sin(th), 3.5 - 1.0 * std::sin(th) + 0.075 * std::cos(th));
  expectStable(runHardCase(buf, 0.8), "thin snow layer on 50 degrees");
}

TEST(HardCases, BallisticFragmentsLeavingTheDomainAreReported) {
  const auto r = runHardCase(R"(
[simulation]
dx = 0.1
end_time = 1
[domain]
min = [0, 0, 0]
max = [2, 1, 2]
walls = "open"
[terrain]
plane = { point = [0, 0, 0.2], normal = [0, 0, 1] }
boundary = "slip"
[[materials]]
name = "rock"
preset = "rock"
[[bodies]]
material = "rock"
shape = "sphere"
center = [1.0, 0.5, 0.6]
radius = 0.3
velocity = [30, 0, -30]
)", 0.3);
  expectStable(r, "fragments leaving the domain");
  EXPECT_GT(r.massRemoved, 0.0);
}

TEST(HardCases, BrittleRockColumnCollapseWithChi1e10) {
  // Cohesion 1 kPa: the 2 m column (53 kPa at its base) yields at the foot, loses its cohesion and
  // peak friction on first yield, and slumps.
  expectStable(runHardCase(R"(
[simulation]
dx = 0.1
end_time = 1
[domain]
min = [0, 0, 0]
max = [4, 0.4, 2.5]
walls = "slip"
[terrain]
plane = { point = [0, 0, 0], normal = [0, 0, 1] }
boundary = "friction"
friction = 0.5
[[materials]]
name = "rock"
preset = "rock"
cohesion = 1e3
[[bodies]]
material = "rock"
shape = "box"
min = [0, 0, 0]
max = [0.6, 0.4, 2.0]
)", 1.0), "brittle column collapse");
}

TEST(HardCases, StiffRockOnSoftSnowDensityRatioElevenStiffnessRatioThousand) {
  // Rock 2700 kg/m3 with E = 3e9 Pa (elastic_scale 100 on the preset) on snow 250 kg/m3, 3e6 Pa.
  expectStable(runHardCase(R"(
[simulation]
dx = 0.1
end_time = 1
[domain]
min = [0, 0, 0]
max = [1.2, 0.6, 1.2]
walls = "slip"
[[materials]]
name = "snow"
preset = "snow"
[[materials]]
name = "rock"
preset = "rock"
elastic_scale = 100
[[bodies]]
material = "snow"
shape = "box"
min = [0, 0, 0]
max = [1.2, 0.6, 0.3]
[[bodies]]
material = "rock"
shape = "box"
min = [0.4, 0.15, 0.35]
max = [0.7, 0.45, 0.65]
velocity = [0, 0, -5]
)", 0.25), "stiff rock on soft snow");
}

TEST(HardCases, NonFiniteStateStopsTheRunNamingStepParticleMaterialAndPosition) {
  auto sim = test::makeSimulation(impactScene("preset = \"snow\"", "min = [0, 0, 0]\nmax = [3, 1, 0.6]"));
  sim->step();
  sim->groups()[1]->particles.v[5] = Vec3(std::nan(""), 0, 0); // a corrupted particle of "target"
  try {
    sim->step();
    FAIL() << "NaN went unnoticed";
  } catch (const NumericalError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find("step 2"), std::string::npos) << msg;
    EXPECT_NE(msg.find("particle"), std::string::npos) << msg;
    EXPECT_NE(msg.find("'target'"), std::string::npos) << msg;
    EXPECT_NE(msg.find(" at ("), std::string::npos) << msg;
  }
}
