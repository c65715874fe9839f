// Quasi-two-dimensional granular column collapse against the run-out scaling of Lube et al.
// (2005, Phys. Rev. E 72:041301): (L_inf - L0)/L0 = 1.2 a for small aspect ratios and
// 1.9 a^(2/3) for large ones, the regime change lying at a ~ 1.8-2.8. The coefficients are
// those quoted by Lagree, Staron & Popinet (2011, JFM 686:378, eq. 3.1) for Lube's sand,
// rice and sugar. Cohesionless Drucker-Prager sand (phi = 32, plane-strain cone fit, as the
// channel is two cells wide) on a rough bed (basal friction = tan 32).
#include "tools/validation_cases.h"

#include <cstdio>
#include <gtest/gtest.h>

using namespace talus::validation;

TEST(ColumnCollapse, RunOutFollowsLubeScalingOnBothSidesOfTheRegimeChange) {
  // The tall column ends in a thin, fragmenting front, so its run-out is resolution-sensitive:
  // -18%, -3% and +20% at 8, 12 and 16 cells across L0 (docs/performance.md lists the spread).
  // The test runs 12 cells; the low column converges (-1% at 20 cells).
  for (const auto& [aspect, cells] : {std::pair<double, double>{0.8, 20}, {5.0, 12}}) {
    const ColumnCollapseResult r = columnCollapse(aspect, {cells, 8, 0.4});
    std::printf("  a = %.1f: run-out %.3f, Lube %.3f (%+.1f%%), final rms speed %.3f m/s\n", aspect, r.runOut,
                r.reference, 100 * r.relError, r.finalRmsSpeed);
    EXPECT_LT(std::abs(r.relError), 0.20) << "a = " << aspect;
    EXPECT_LT(r.finalRmsSpeed, 0.02 * r.collapseSpeedScale) << "deposit not at rest at a = " << aspect;
  }
}
