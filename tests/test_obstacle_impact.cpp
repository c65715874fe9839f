// A dam break onto a box, MARIN's experiment (Kleefsman et al. 2005, SPHERIC Test 2): the water
// depth at four gauges and the box's horizontal load against the records
// (tools/validation_obstacle.cpp, tools/validation_kleefsman_data.h; the resolutions and sound
// speeds are in docs/convergence.md, "Dam break onto a box").
#include "tools/validation_cases.h"

#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>

using namespace talus;

namespace {

void print(const validation::ObstacleImpactResult& r) {
  using R = validation::ObstacleImpactResult;
  std::printf("t s | depth m at x = 0.496 0.992 1.488 2.638 (MARIN) | box load N (MARIN), 0.05 s mean\n");
  // Every 0.05 s through the impact, every 0.25 s after it.
  for (size_t i = 0; i < r.t.size(); i += (r.t[i] < 1.5 - 1e-9 ? 1 : 5) * R::kDepthEvery) {
    std::printf("%4.2f |", r.t[i]);
    for (size_t k = 0; k < r.depth.size(); ++k)
      std::printf(" %.3f (%.3f)", r.depth[k][i], r.depthExp[k][i / R::kDepthEvery]);
    std::printf(" | %5.0f (%5.0f)\n", r.forceFiltered[i], r.forceExpFiltered[i]);
  }
  for (size_t k = 0; k < r.depth.size(); ++k)
    std::printf("x %.3f: depth error %.3f, arrival %.3f s (%.3f)\n", R::gaugeX()[k], r.depthError[k], r.arrival[k],
                r.arrivalExp[k]);
  std::printf("load: peak %.0f N at %.2f s (%.0f at %.2f), 0.6-1.0 s %.0f N (%.0f); water lost %.4f; momentum "
              "balance %.1e; %zu particles, %llu steps, %.1f s\n",
              r.peak, r.peakT, r.peakExp, r.peakTExp, r.plateau, r.plateauExp, r.lostWater, r.momentumImbalance,
              r.particles, r.steps, r.wallSeconds);
}

} // namespace

// About 10 cells across the 0.55 m depth: dx = 0.5/9 m (5.56 cm), so the half tank's walls lie on
// node rows (15 840 particles), c = 50 m/s, 0-6 s. Asserted:
//  - the depth in front of the box (x = 0.992 m) and in the reservoir (2.638 m), the two gauges
//    SPHERIC's comparisons use, as sum |d - d_exp| / sum d_exp over 0-6 s: under 0.20. Measured
//    0.102 and 0.102 (0.153 and 0.069 at dx 3.6 cm): the 10 % that docs' validation table calls
//    fair is not met in front of the box; much of the difference is the bore that returns from
//    the far wall arriving late at 4.5-5 s (docs/convergence.md);
//  - the front's arrival at 1.488 and 0.992 m within 0.05 s of the gauges' first 0.01 m
//    (measured +0.046 and +0.011 s, the crossing interpolated between the 0.01-s samples);
//  - the box's load while the flow presses on it (0.6-1.0 s, 0.05 s means) within 15 % of the
//    load the front face's four pressure sensors give (measured -4 %; +21 % at dx 3.6 cm). This
//    pins the configuration, it does not validate the load: the load grows as the time step
//    shrinks, because each edge of the box the water turns round takes momentum per step
//    (+41 % at a 4x smaller step; tools/studies/box_edges.sh, docs/convergence.md);
//  - the loads are what the water lost: every collider's x impulse against the water's x momentum
//    lost, 1e-3 of the largest x momentum (measured 9.9e-5);
//  - water kept (under 1 % lost over the open top).
// Not met, and pinned at what the model gives: the impact's peak load, 259 N against 432 N
// (-40 %; -15 % at dx 3.6 cm). The bounds (0.55 to 1.15 of the record) show a change that
// makes it worse, or one to the contact at edges that moves it (then check it against the
// table in docs/convergence.md, not these bounds).
TEST(DamBreak, OntoABoxTheDepthsFollowMarinsGaugesAndTheBoxTakesTheFlowsLoad) {
  using R = validation::ObstacleImpactResult;
  validation::Resolution res;
  res.cells = 10;
  const auto r = validation::obstacleImpact(res);
  print(r);
  ASSERT_EQ(r.depth.size(), 4u);
  ASSERT_EQ(R::gaugeX()[1], 0.992);
  ASSERT_EQ(R::gaugeX()[3], 2.638);
  EXPECT_LT(r.depthError[1], 0.20);
  EXPECT_LT(r.depthError[3], 0.20);
  for (size_t k : {1, 2}) EXPECT_NEAR(r.arrival[k], r.arrivalExp[k], 0.05) << "x " << R::gaugeX()[k];
  EXPECT_NEAR(r.plateau / r.plateauExp, 1.0, 0.15);
  EXPECT_GT(r.peak / r.peakExp, 0.55);
  EXPECT_LT(r.peak / r.peakExp, 1.15);
  EXPECT_LT(r.momentumImbalance, 1e-3);
  EXPECT_LT(r.lostWater, 0.01);
}
