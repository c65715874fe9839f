// Grid memory follows the material, not the domain's bounding box.
#include "test_support.h"
#include "tools/validation_cases.h"

#include <gtest/gtest.h>

using namespace talus;

namespace {
/// The layer over a 1 km square domain.
std::string layerScene(double layerSide, double domainHeight) {
  return validation::thinLayerScene(layerSide, 1000, domainHeight);
}
} // namespace

TEST(SparseGrid, OneCellLayerOverOneKilometreAllocatesBlocksForTheLayerOnly) {
  auto sim = test::makeSimulation(layerScene(1000, 1000));
  sim->step();
  const size_t blocks = sim->grid().blockCount();
  // The layer spans 25 x 25 blocks of 40 m; with the +1 stencil closure at most 26 x 26 x 2.
  // A dense box would need 25^3 = 15625 blocks.
  EXPECT_LE(blocks, 26u * 26u * 2u);
  EXPECT_GE(blocks, 25u * 25u);
  // Doubling the box height changes nothing; a quarter of the layer needs about a quarter.
  auto taller = test::makeSimulation(layerScene(1000, 2000));
  taller->step();
  EXPECT_EQ(taller->grid().blockCount(), blocks);
  auto quarter = test::makeSimulation(layerScene(500, 1000));
  quarter->step();
  const double ratio = double(quarter->grid().blockCount()) / double(blocks);
  // Owning blocks 13^2 against 25^2 plus the +1 closure: (14/26)^2 = 0.29.
  EXPECT_NEAR(ratio, 196.0 / 676.0, 0.01);
  // Node storage is 512 nodes x 16 bytes per block, nothing per empty block.
  EXPECT_LT(double(sim->gridBytes()), 1.2 * double(blocks) * 512 * sizeof(Vec4));
}
