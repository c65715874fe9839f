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
// default: the far-field wave depends on c up to there, docs/impulse_waves.md). Asserted:
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
