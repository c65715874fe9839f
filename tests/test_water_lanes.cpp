// The Tait water's update in SIMD lanes (materials/water_lanes.h) against TaitWaterModel::update,
// on random states, on every Highway target this machine runs.
#include "materials/water_lanes.h"
#include "simd_targets.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

namespace talus {
namespace {

constexpr double kDt = 1e-4;

/// Random particles: dt |C| up to 0.02 (a strong compression or expansion per step), J - 1 down
/// to -1 % (the Tait law's range at B = 3e8 Pa: 2 MPa at -0.1 %), stored as floats.
std::vector<WaterLanes> randomStates(unsigned seed) {
  std::mt19937_64 rng(seed);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<WaterLanes> chunks(300);
  for (WaterLanes& io : chunks) {
    std::memset(&io, 0, sizeof io);
    for (int k = 0; k < kWaterLanes; ++k) {
      for (int r = 0; r < 9; ++r) io.C[r][k] = double(float(200 * u(rng)));
      io.dJ[k] = double(float(-0.005 * (1 + u(rng))));
    }
  }
  return chunks;
}

/// |a - b| within `ulps` units of a float's last place of `scale`.
::testing::AssertionResult closeAsFloats(double a, double b, double scale, const char* what) {
  const double tol = 2 * std::ldexp(1.0, -23) * scale;
  if (std::abs(a - b) <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << what << ": lanes " << a << ", scalar " << b << ", tolerance " << tol;
}

void checkModel(const TaitWaterModel& model) {
  const std::vector<WaterLanes> in = randomStates(5);
  std::vector<WaterLanes> best = in;
  int compressed = 0;
  for (size_t c = 0; c < in.size(); ++c) {
    const int n = 1 + int(c % kWaterLanes);
    updateWaterLanes(model, kDt, n, best[c]);
    for (int k = 0; k < n; ++k) {
      // The scalar update, as FluidGroup ran it before the lanes.
      Mat3 C;
      for (int r = 0; r < 9; ++r) C(r / 3, r % 3) = Real(in[c].C[r][k]);
      float dJ = float(in[c].dJ[k]);
      Sym3 tau;
      model.update(dJ, C, kDt, tau);
      compressed += dJ < 0;
      // Both round to float the J - 1 of the same product in another order: within 2 ulps of it.
      EXPECT_TRUE(closeAsFloats(double(float(best[c].dJ[k])), double(dJ), std::abs(double(dJ)), "J - 1"));
      const double t[6] = {tau.xx, tau.yy, tau.zz, tau.xy, tau.xz, tau.yz};
      double scale = 0;
      for (double v : t) scale = std::max(scale, std::abs(v));
      for (int r = 0; r < 6; ++r) EXPECT_TRUE(closeAsFloats(double(Real(best[c].tau[r][k])), t[r], scale, "tau"));
    }
  }
  // Of the 2 550 particles, those stretched past J = 1 meet the tension cut; the rest compress.
  EXPECT_GT(compressed, 1000) << "the states exercise the equation of state";
  forEachSimdTarget([&] {
    for (size_t c = 0; c < in.size(); ++c) {
      WaterLanes io = in[c];
      const int n = 1 + int(c % kWaterLanes);
      updateWaterLanes(model, kDt, n, io);
      for (int k = 0; k < n; ++k) {
        ASSERT_EQ(std::memcmp(&io.dJ[k], &best[c].dJ[k], 8), 0) << "chunk " << c;
        for (int r = 0; r < 6; ++r) ASSERT_EQ(std::memcmp(&io.tau[r][k], &best[c].tau[r][k], 8), 0) << "chunk " << c;
      }
    }
  });
}

TEST(WaterLanes, InviscidMatchesTheScalarUpdateWithinTwoFloatUlpsAndEveryTargetBitForBit) {
  checkModel(TaitWaterModel{});
}

TEST(WaterLanes, ViscousWithTensionMatchesTheScalarUpdateAndEveryTargetBitForBit) {
  // A viscous slurry (1 kPa s: the deviatoric stress of a 200 1/s shear, 4e5 Pa, is the pressure's
  // order) that carries up to 1 MPa of tension.
  TaitWaterModel m;
  m.viscosity = 1e3;
  m.maxTension = 1e6;
  checkModel(m);
}

} // namespace
} // namespace talus
