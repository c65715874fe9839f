// A granular slide into still water in a quasi-2-D flume (Fritz, Hager & Minor 2004's set-up),
// read by the run's own wave gauges, against Heller & Hager (2010)'s impulse-product relations
// (tools/validation_impulse_wave.cpp; all five configurations at two resolutions are in
// docs/convergence.md, "Impulse waves").
#include "tools/validation_cases.h"

#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>

using namespace talus;

// P = 0.90, alpha = 45 degrees, h/dx = 8 (about 25 s on two cores).
// What holds, and is asserted:
//  - its height decays with distance as Heller & Hager's H ~ X^(-0.8/3) beyond x_M (the exponent
//    within 0.1: their fit's exponent carries the scatter of 211 runs);
//  - the water stays in the flume (under 1 % thrown over the open top).
// What does not, and is pinned at what the model gives: the amplitude. Heller & Hager predict
// a_M/h = 0.41 and H_M/h = 0.51 here; the model's largest crest is 1.0 h at X = 2 (water heaped on
// the slide front as it enters) and its travelling crest 0.52-0.57 h at X = 4-6, 30-40 % above
// the relation (the goal of issue 34 is 20 %; the runs that bear on why are in
// docs/convergence.md). The bounds below hold the travelling crest between the relation and
// +60 %, so a change that makes it worse, or that brings it within the goal, shows here.
// The crest's celerity between X = 6 and X = 12 is also short of what the experiments show:
// Heller & Hager's leading crests travel at about the solitary wave's sqrt(g (h + a)) (1.21
// sqrt(gh) for the model's mean crest a/h = 0.47 there); the model's moves at 1.10 sqrt(gh), a
// long wave's speed corrected for about half its amplitude. Asserted: between the linear long
// wave's sqrt(gh) and the solitary wave's (the crest's time is sampled every 0.05 in T over about
// 5, a 1 % uncertainty).
TEST(ImpulseWave, ASlideIntoAFlumeMakesASolitaryCrestThatDecaysAsHellerAndHagerFound) {
  const validation::ImpulseWaveCase& c = validation::impulseWaveCases()[1];
  ASSERT_STREQ(c.name, "p09_a45");
  validation::Resolution r;
  r.cells = 8;
  const auto w = validation::impulseWave(c, r);
  std::printf("P %.3f: a_M/h %.3f (H&H %.3f), H_M/h %.3f (%.3f) at X %.1f (%.1f); decay exponent %.3f; "
              "centroid speed / V_s %.3f; water lost %.4f; %zu particles, %llu steps, %.1f s\n",
              w.P, w.aM, w.aMRef, w.HM, w.HMRef, w.xM, w.xMRef, w.decayExponent, w.centroidSpeedRatio, w.lostWater,
              w.particles, w.steps, w.wallSeconds);
  auto at = [&](double X) {
    for (size_t k = 0; k < w.X.size(); ++k)
      if (std::abs(w.X[k] - X) < 1e-9) return k;
    ADD_FAILURE() << "no gauge at X = " << X;
    return size_t(0);
  };
  const size_t k6 = at(6), k12 = at(12);
  double a = 0;
  for (size_t k = k6; k <= k12; ++k) a += w.crest[k] / double(k12 - k6 + 1);
  const double celerity = 6 / (w.crestT[k12] - w.crestT[k6]);
  EXPECT_GT(celerity, 1.0) << "crest celerity in sqrt(gh), mean a/h " << a;
  EXPECT_LT(celerity, std::sqrt(1 + a)) << "crest celerity in sqrt(gh), mean a/h " << a;
  EXPECT_NEAR(w.decayExponent, -0.8 / 3, 0.1);
  EXPECT_LT(w.lostWater, 0.01);
  // The travelling crest (X = 4-6) against a_M = 4/9 P^0.8: see above.
  double travelling = 0;
  for (double X : {4.0, 5.0, 6.0}) travelling = std::max(travelling, w.crest[at(X)]);
  EXPECT_GT(travelling / w.aMRef, 1.0);
  EXPECT_LT(travelling / w.aMRef, 1.6);
}
