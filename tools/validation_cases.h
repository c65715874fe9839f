// Validation cases with analytic or published references, runnable at any resolution: the
// test suite runs them at one resolution and asserts tolerances; `talus work-precision` refines
// them to measure error against cost.
#pragma once

#include <string>
#include <vector>

namespace talus::validation {

struct Resolution {
  double cells = 1;  ///< case-specific resolution (cells across the characteristic length)
  int particlesPerCell = 8;
  double cfl = 0.4;
};

/// What every run reports, besides its error.
struct RunCost {
  size_t particles = 0;
  unsigned long long steps = 0;
  double wallSeconds = 0;
};

/// Block on a 30-degree plane turned 20 degrees off the grid axes, Coulomb mu through the
/// terrain SDF. cells = cells across the block's 0.2 m height (2 -> dx 0.1). Error: the largest
/// |s / s_exact - 1| once s > 5 cells (s = g t^2 (sin - mu cos) / 2).
struct SlidingBlockResult : RunCost {
  double maxRelError = 0;
  std::vector<double> t, s, exact; ///< samples every 0.05 s
  double restDisplacement = 0;     ///< |s| at the end when the block should stay (mu > tan)
  double restSpeed = 0;
};
SlidingBlockResult slidingBlock(double mu, const Resolution& r, double endTime = 0.9, double gravityRamp = 0);

/// Fixed-free elastic bar (L = 1 m, nu = 0), first mode excited. cells = cells along the bar.
/// Error: |T / (4L/c) - 1|.
struct ElasticBarResult : RunCost {
  double period = 0, exact = 0, relError = 0;
};
ElasticBarResult elasticBar(const Resolution& r);

/// Martin & Moyce (1952) dam break, n^2 = 2, quasi-2-D. cells = cells across the column width a.
/// Reads the digitised data file; error: mean and max |Z / Z_exp - 1| for T <= 3.
struct DamBreakResult : RunCost {
  std::vector<double> T, Z, Zexp;
  double meanRelError = 0, maxRelError = 0;
};
DamBreakResult damBreak(const std::string& dataFile, const Resolution& r);

/// Quasi-2-D granular column collapse (plane-strain Drucker-Prager, phi 32, rough bed), run-out
/// (L_inf - L0)/L0 against Lube et al. (2005): 1.2 a (small a), 1.9 a^(2/3) (large a).
/// cells = cells across the column's initial length L0.
struct ColumnCollapseResult : RunCost {
  double runOut = 0, reference = 0, relError = 0, finalRmsSpeed = 0, collapseSpeedScale = 0;
};
ColumnCollapseResult columnCollapse(double aspect, const Resolution& r);

/// A one-cell-thick elastic layer (dx = 5 m, one particle per cell, 5 m thick at z = 500 m) over
/// a layerSide square in a domainSide x domainSide x domainHeight box: what the sparse grid must
/// store in proportion to the layer, not the box (test_sparse_grid, `talus work-precision`).
std::string thinLayerScene(double layerSide, double domainSide, double domainHeight);

} // namespace talus::validation
