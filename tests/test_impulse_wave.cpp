// A granular slide into still water in a quasi-2-D flume (Fritz, Hager & Minor 2004's set-up),
// read by the run's own wave gauges, against Heller & Hager (2010)'s impulse-product relations
// (tools/validation_impulse_wave.cpp; the five configurations, two resolutions and four sound
// speeds are in docs/impulse_waves.md).
#include "tools/validation_cases.h"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>

using namespace talus;

// P = 0.90, alpha = 45 degrees, h/dx = 8, water at c = 160 sqrt(gh) = 272 m/s (the case's
// default), CFL 0.4. The wave depends on the step, not on c at a given step, and is not yet
// converged in it (docs/impulse_waves.md, "Not the sound speed: the time step"): the figures
// below hold at this step only. Asserted:
//  - the leading wave's height beyond x_M against H/h = 3/4 (P X^(-1/3))^0.8, mean |error| 10 %
//    (measured 3.5 %; the experiments scatter by about 30 % around the relation, the goal
//    is 20 %), and its decay exponent within 0.1 of their -0.8/3;
//  - the travelling crest (the largest at X = 4-6, where it has left the slide) against
//    a_M/h = 4/9 P^0.8: 20 %, the goal (measured +8 %);
//  - the water stays in the flume (under 1 % thrown over the open top).
// Not met, and pinned at what the model gives: the largest crest of all gauges stands at X = 2.5
// (H&H's x_M = 5.2), 0.75 h against a_M = 0.41 h: water heaped on the entering slide's front.
// The bound (below 2 a_M) shows a change that makes it worse, or brings it within the goal.
TEST(ImpulseWave, ASlideIntoAFlumeMakesTheWaveHellerAndHagerFoundBeyondTheSlide) {
  const validation::ImpulseWaveCase& c = validation::impulseWaveCases()[1];
  ASSERT_STREQ(c.name, "p09_a45");
  validation::Resolution r;
  r.cells = 8;
  const auto w = validation::impulseWave(c, r);
  std::printf("P %.3f, c %.0f m/s: a_M/h %.3f (H&H %.3f), H_M/h %.3f (%.3f) at X %.1f (%.1f); decay error %.3f, "
              "exponent %.3f; water lost %.4f; %zu particles, %llu steps, %.1f s\n",
              w.P, w.soundSpeed, w.aM, w.aMRef, w.HM, w.HMRef, w.xM, w.xMRef, w.decayError, w.decayExponent,
              w.lostWater, w.particles, w.steps, w.wallSeconds);
  auto at = [&](double X) {
    for (size_t k = 0; k < w.X.size(); ++k)
      if (std::abs(w.X[k] - X) < 1e-9) return k;
    ADD_FAILURE() << "no gauge at X = " << X;
    return size_t(0);
  };
  EXPECT_LT(w.decayError, 0.10);
  EXPECT_NEAR(w.decayExponent, -0.8 / 3, 0.1);
  double travelling = 0;
  for (double X : {4.0, 5.0, 6.0}) travelling = std::max(travelling, w.crest[at(X)]);
  EXPECT_NEAR(travelling / w.aMRef, 1.0, 0.2) << "travelling crest a/h " << travelling;
  EXPECT_LT(w.aM / w.aMRef, 2.0);
  EXPECT_LT(w.lostWater, 0.01);
}

// The spatial case: a slide two depths wide (B = 2, P = 1.39, alpha = 45 degrees) into a basin 9 h
// across, mirrored about its axis, at h/dx 4 (39 000 particles), against Evers et al. (2019)'s
// first crest a_c1(r, gamma) (tools/validation_impulse_wave.cpp; h/dx 4, 6 and 9 in
// docs/impulse_waves.md). The crests do not converge: on the axis at r = 4.5 h they read -21 %,
// +7 % and +47 % of a_c1 at h/dx 4, 6 and 9 (the far ones, 0.05-0.1 h, fade below half a cell
// at h/dx 4). So agreement at one resolution is no evidence, and the crest below is pinned at
// what h/dx 4 gives. Asserted:
//  - the first crest's speed on the axis between r = 4.5 and 7.5 h against the relations'
//    c_c1 = 0.95 sqrt(g (h + a_c1)): 10 % (measured +3 %; a celerity, which the coarse grid's
//    damping biases little);
//  - the wave's spreading at r = 4.5 h: the crest at 60 degrees over the crest on the axis against
//    the relations' ratio, 25 % (measured +10 %; +2 % at h/dx 6, -7 % at 9);
//  - the crest on the axis at r = 4.5 h against a_c1: 30 % (measured -21 %; a pin against change,
//    not the 20 %, which no resolution here meets for every gauge);
//  - the water stays in the basin (under 1 % thrown out).
TEST(ImpulseWave, ASlideNarrowerThanTheBasinSpreadsItsWaveAsTheSpatialRelationsSay) {
  validation::Resolution r;
  r.cells = 4;
  const auto w = validation::impulseWave3d(r);
  std::printf("P %.3f, c %.0f m/s, a_0,c1/h %.3f; %zu particles, %llu steps, %.1f s\n", w.P, w.soundSpeed, w.a0,
              w.particles, w.steps, w.wallSeconds);
  auto at = [&](double rh, double deg) {
    for (const auto& g : w.gauges)
      if (g.r == rh && g.gammaDeg == deg) return g;
    ADD_FAILURE() << "no gauge at r/h " << rh << ", " << deg << " degrees";
    return validation::ImpulseWave3dGauge{};
  };
  for (const auto& g : w.gauges)
    std::printf("  r/h %.1f, %2.0f degrees: a_c1/h %.3f at T %.2f (relations %.3f)\n", g.r, g.gammaDeg, g.crest,
                g.crestT, g.ref);
  const auto near = at(4.5, 0), far = at(7.5, 0), side = at(4.5, 60);
  const double speed = (far.r - near.r) / (far.crestT - near.crestT);
  const double celerity = 0.95 * std::sqrt(1 + 0.5 * (near.ref + far.ref));
  std::printf("  crest speed on the axis %.3f sqrt(gh) (relations %.3f)\n", speed, celerity);
  EXPECT_NEAR(speed / celerity, 1.0, 0.10);
  EXPECT_NEAR(near.crest / near.ref, 1.0, 0.30);
  EXPECT_NEAR((side.crest / near.crest) / (side.ref / near.ref), 1.0, 0.25);
  EXPECT_LT(w.lostWater, 0.01);
}
