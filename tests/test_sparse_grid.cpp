// Grid memory follows the material, not the domain's bounding box.
#include "test_support.h"

#include <gtest/gtest.h>

using namespace talus;

namespace {
std::string layerScene(double layerSide, double domainHeight) {
  char buf[1024];
  std::snprintf(buf, sizeof buf, R"(
[simulation]
dx = 5.0
particles_per_cell = 1
end_time = 1.0
[domain]
min = [0, 0, 0]
max = [1000, 1000, %g]
[[materials]]
name = "snowlike"
model = "elastic"
density = 300
youngs_modulus = 1e6
[[bodies]]
material = "snowlike"
shape = "box"
min = [0, 0, 500]
max = [%g, %g, 505]
)", domainHeight, layerSide, layerSide);
  return buf;
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
