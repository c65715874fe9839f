// Tait equation of state and the J update of the fluid group (physics.md 4.3).
#include "materials/tait_water.h"
#include "test_support.h"

#include <gtest/gtest.h>

using namespace talus;

TEST(TaitWater, PressureSoundSpeedAndRestStateMatchTheEquationOfState) {
  TaitWaterModel w; // B = 3e8, k = 7
  EXPECT_DOUBLE_EQ(w.pressure(1.0), 0.0);
  EXPECT_NEAR(w.pressure(0.999), 3e8 * (std::pow(0.999, -7) - 1), 1e-3);
  EXPECT_NEAR(w.soundSpeed(1000), std::sqrt(7 * 3e8 / 1000), 1e-9); // 1449 m/s
  for (double p : {0.0, 1e4, 1e6, 1e7}) EXPECT_NEAR(w.pressure(w.restJ(p)), p, 1e-6 * (p + 1));
  // 1 per mil density change for ~2 MPa: the paper's eta ~ 1e-3 at v ~ c/30.
  EXPECT_NEAR(1 / w.restJ(2.1e6) - 1, 1e-3, 1e-4);
}

TEST(TaitWater, CompressionFollowsDetOfTheVelocityGradientAndTensionIsCut) {
  TaitWaterModel w;
  float dJ = 0; // J - 1
  Sym3 tau;
  Mat3 C = Mat3::Zero();
  C(0, 0) = -0.5; // uniaxial compression rate
  w.update(dJ, C, 1e-3, tau);
  EXPECT_NEAR(dJ, -0.5e-3, 1e-10);
  const double J = 1 + double(dJ);
  EXPECT_NEAR(tau.xx, -J * w.pressureOfStrain(dJ), 1e-6 * w.pressureOfStrain(dJ));
  EXPECT_EQ(tau.xy, 0);
  // A tiny compression is still resolved: 1e-9 volumetric strain is 2.1 Pa with B = 3e8.
  float tiny = -1e-9f;
  EXPECT_NEAR(w.pressureOfStrain(tiny), 2.1, 0.01);
  // Stretching beyond J = 1 is cut: no tension, no cavitation.
  C(0, 0) = 2.0;
  for (int i = 0; i < 10; ++i) w.update(dJ, C, 1e-3, tau);
  EXPECT_EQ(dJ, 0.0f);
  EXPECT_EQ(tau.xx, 0);
  // With max_tension, the water carries up to that tension.
  w.maxTension = 1e5;
  for (int i = 0; i < 10; ++i) w.update(dJ, C, 1e-3, tau);
  EXPECT_NEAR(w.pressureOfStrain(dJ), -1e5, 1e-2);
}

TEST(TaitWater, EachWaterMaterialKeepsItsOwnCompressionForItsSoundSpeed) {
  // Review defect: the most compressed particle of all water groups set every group's sound
  // speed. A deep column (J well below 1) and a separate shallow pool must each keep their own.
  auto sim = test::makeSimulation(R"(
[simulation]
dx = 0.1
end_time = 1
[domain]
min = [0, 0, 0]
max = [2, 1, 12]
walls = "slip"
[[materials]]
name = "deep"
model = "water"
density = 1000
sound_speed = 20
[[materials]]
name = "shallow"
model = "water"
density = 1000
sound_speed = 20
[[bodies]]
material = "deep"
shape = "box"
min = [0, 0, 0]
max = [0.8, 1, 10]
[[bodies]]
material = "shallow"
shape = "box"
min = [1.2, 0, 0]
max = [2, 1, 0.2]
)");
  sim->step();
  const MaterialGroup& deep = *sim->groups()[0];
  const MaterialGroup& shallow = *sim->groups()[1];
  // 10 m of water with B = rho c^2 / 7: J ~ 0.96 at the bottom, c(J) ~ 15% above c(1).
  EXPECT_GT(deep.waveSpeed(), 1.1 * 20);
  EXPECT_LT(shallow.waveSpeed(), 1.02 * 20);
}
