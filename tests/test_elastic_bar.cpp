// First longitudinal mode of a fixed-free elastic bar: period T = 4 L / c, c = sqrt(E / rho).
#include "tools/validation_cases.h"

#include <cstdio>
#include <gtest/gtest.h>

using namespace talus::validation;

TEST(ElasticBar, FirstModePeriodWithinTwoPercentOfFourLOverC) {
  // nu = 0 makes the bar speed sqrt(E/rho) equal the P-wave speed, so lateral inertia and
  // confinement cannot blur the comparison. 32 cells along the bar.
  const ElasticBarResult r = elasticBar({32, 8, 0.4});
  std::printf("  period %.5f s, 4L/c = %.5f s, error %+.2f%%\n", r.period, r.exact, 100 * r.relError);
  EXPECT_LT(std::abs(r.relError), 0.02);
}
