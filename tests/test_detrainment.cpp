// A forest's detrainment (engine/detrainment.h) against its closed form: on an infinite layer
// sliding at constant speed u (Coulomb friction tan 30 degrees on a 30 degree slope balances
// gravity), AvaFrame's dm/dt = -detK A / u takes mass at a constant rate, so
// M(t) = M0 - detK A integral(dt / u). And AvaFrame's thresholds: slow or thin detrains without
// drag, fast and thick drags without detraining.
#include "engine/detrainment.h"
#include "forest_plug.h"
#include "test_support.h"

#include <cmath>
#include <gtest/gtest.h>

using namespace talus;

namespace {

const double kMuBalanced = std::tan(30 * M_PI / 180);

double totalMass(const Simulation& sim) {
  double m = 0;
  for (const MaterialGroup* g : sim.groups())
    for (Real p : g->particles.mass) m += double(p);
  return m;
}

/// Mass the scene's forests detrained (0 when none detrains: the phase is not built then).
double detrainedMass(const Simulation& sim) {
  for (const auto& s : sim.sources())
    if (const auto* d = dynamic_cast<const Detrainment*>(s.get())) return d->detrainedMass();
  return 0;
}

struct LayerRun {
  double m0 = 0, m = 0, detrained = 0, lossExpected = 0, u = 0;
};

/// The layer (h thick, 0.8 x 0.8 m periodic patch, dx 0.1) at speed u0 for `seconds` under a
/// forest of drag cRes with `regionKeys`; the loss expected integrates detK A / u over the
/// measured mean speed (trapezoid, 0.1 s samples).
LayerRun runLayer(const std::string& name, double h, double u0, double cRes, double seconds, double detK,
                  const std::string& regionKeys = "") {
  const std::string dir = test::tempDir(name);
  auto sim = test::makeSimulation(test::forestPlugScene(dir, h, 0.1, kMuBalanced, cRes, 0, regionKeys, u0));
  LayerRun r;
  r.m0 = totalMass(*sim);
  const double area = 0.8 * 0.8;
  double uPrev = sim->meanVelocity().norm();
  for (double t = 0.1; t <= seconds + 1e-9; t += 0.1) {
    sim->advanceTo(t);
    const double u = sim->meanVelocity().norm();
    r.lossExpected += detK * area * 0.05 * (1 / uPrev + 1 / u);
    uPrev = u;
  }
  r.m = totalMass(*sim), r.detrained = detrainedMass(*sim), r.u = uPrev;
  std::printf("  %s: M0 %.4f kg, M %.4f kg, detrained %.4f kg (expected %.4f), u %.3f m/s\n", name.c_str(), r.m0, r.m,
              r.detrained, r.lossExpected, r.u);
  return r;
}

} // namespace

TEST(Detrainment, AvaFramesThresholdsSplitDragAndDetrainment) {
  // com1DFATools.updateResCoeffFields: detrain where u <= 6 m/s or h <= 0.6 m, drag where both
  // are above, neither above 40 m/s or 10 m; without detrainment (detK = 0) the drag everywhere.
  const DetrainmentThresholds t;
  const double cases[][2] = {{3, 0.4}, {3, 0.8}, {8, 0.4}, {8, 0.8}, {6, 0.8}, {8, 0.6}, {41, 0.4}, {8, 11}, {41, 11}};
  const bool detrain[] = {true, true, true, false, true, true, false, false, false};
  const bool drag[] = {false, false, false, true, false, false, false, false, false};
  for (size_t i = 0; i < std::size(cases); ++i) {
    const double u = cases[i][0], h = cases[i][1];
    EXPECT_EQ(Detrainment::detrains(h, u, t), detrain[i]) << "u " << u << " h " << h;
    EXPECT_EQ(ResistedLaw::drags(u, h, 5.0), drag[i]) << "u " << u << " h " << h;
    EXPECT_TRUE(ResistedLaw::drags(u, h, 0.0)); // AvaFrame's detrainment = False
  }
}

TEST(Detrainment, ASlowThinLayerLosesMassAtFeistlsRate) {
  // 0.4 m of density 300 at 3 m/s under AvaFrame's default forest (cResH 0.01, detK 5 Pa): below
  // both lower thresholds, so no drag; the layer loses detK A / u = 1.07 kg/s of its 76.8 kg.
  const LayerRun r = runLayer("detrain_slow", 0.4, 3.0, 0.01, 3.0, 5.0);
  // The ledger: what the particles lost is what the forest holds, to round-off.
  EXPECT_NEAR(r.m + r.detrained, r.m0, 1e-9 * r.m0);
  // Each cell column loses detK dx^2 dt / u exactly, so the loss is the closed form's up to the
  // speed's variation within a 0.1 s sample (measured: 0.08 %); 0.5 % fails a rate off by 1 %.
  EXPECT_NEAR(r.detrained, r.lossExpected, 0.005 * r.lossExpected);
  EXPECT_GT(r.detrained, 0.03 * r.m0); // 3.2 kg: not a vanishing effect
  // No drag: the layer keeps its speed (the balanced friction's drift, measured under 0.5 %).
  EXPECT_NEAR(r.u, 3.0, 0.03);
}

TEST(Detrainment, AFastThickFlowIsDraggedNotDetrainedAndAFastThinOneTheReverse) {
  // 0.8 m at 8 m/s: the drag du/dt = -cResH u^2 / h alone, u(t) = 1 / (1/u0 + cResH t / h);
  // cResH 0.02 1/m takes it to 6.67 m/s in 1 s (still above 6 m/s). Measured within 0.05 %.
  const LayerRun thick = runLayer("detrain_thick", 0.8, 8.0, 0.02, 1.0, 5.0);
  EXPECT_EQ(thick.detrained, 0.0);
  EXPECT_EQ(thick.m, thick.m0);
  const double uExact = 1 / (1 / 8.0 + 0.02 * 1.0 / 0.8);
  EXPECT_NEAR(thick.u, uExact, 0.005 * uExact); // without the drag 8.0: 20 % off
  // 0.4 m at 8 m/s: thinner than 0.6 m, so detrainment (at 8 m/s) and no drag.
  const LayerRun thin = runLayer("detrain_thin", 0.4, 8.0, 0.02, 1.0, 5.0);
  EXPECT_NEAR(thin.detrained, thin.lossExpected, 0.005 * thin.lossExpected);
  EXPECT_NEAR(thin.u, 8.0, 0.04); // the drag would make it 5.71 m/s
  // detrainment = 0 (AvaFrame's detrainment = False): the forest only drags, at any thickness.
  const LayerRun off = runLayer("detrain_off", 0.4, 8.0, 0.02, 1.0, 0.0, "detrainment = 0");
  EXPECT_EQ(off.detrained, 0.0);
  const double uThin = 1 / (1 / 8.0 + 0.02 * 1.0 / 0.4);
  EXPECT_NEAR(off.u, uThin, 0.005 * uThin);
}
