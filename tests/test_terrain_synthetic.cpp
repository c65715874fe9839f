// Synthetic alpine DEMs: their defining geometry, georeferencing, and scenes that use them.
#include "io/terrain/synthetic_dem.h"
#include "io/config/toml_reader.h"
#include "terrain_test_support.h"

#include <cmath>
#include <gtest/gtest.h>

using namespace talus;

namespace {

DemRaster synth(const std::string& spec) {
  auto t = readTomlString(spec, "synthetic.toml");
  DemRaster d = makeSyntheticDem(*t);
  t->checkAllUsed();
  return d;
}

/// Slope angle (degrees) along x at world (x, y), from the bilinear surface over +-2 cells.
double slopeAlongX(const DemRaster& d, double x, double y) {
  const HeightField f(d);
  const double e = 2 * d.grid.cellSize;
  return std::atan((f.height(x - e, y) - f.height(x + e, y)) / (2 * e)) * 180 / M_PI;
}

} // namespace

TEST(TerrainSynthetic, EveryKindIsFiniteAndGeoreferencedInLv95) {
  for (const auto& k : syntheticDemKinds()) {
    const DemRaster d = synth("kind = \"" + k.name + "\"\ncell_size = 10\n");
    EXPECT_EQ(countNodata(d), 0u) << k.name;
    float lo = INFINITY;
    for (float h : d.height) lo = std::min(lo, h);
    EXPECT_GT(lo, 0.f) << k.name;
    EXPECT_DOUBLE_EQ(d.grid.originX, 2600000) << k.name;
    EXPECT_DOUBLE_EQ(d.grid.originY - d.grid.ny * d.grid.cellSize, 1200000) << k.name;
    EXPECT_NE(crsName(d.grid.crsWkt).find("2056"), std::string::npos) << k.name;
  }
}

TEST(TerrainSynthetic, SlopeValleyHasItsSlopeAngleAndAFlatFloor) {
  const DemRaster d = synth("kind = \"slope_valley\"\nslope_angle = 38\ncell_size = 2\n");
  const double x0 = 2600000, y = 1200400;
  // Mid-slope (150 m plateau + 300 m), far from the 40 m transitions: the angle itself.
  EXPECT_NEAR(slopeAlongX(d, x0 + 450, y), 38, 0.2);
  // Valley floor (150 + 600 + 200 m): flat along x.
  EXPECT_NEAR(slopeAlongX(d, x0 + 950, y), 0, 0.2);
  // Counter slope rises again (negative angle along +x).
  EXPECT_NEAR(slopeAlongX(d, x0 + 1300, y), -20, 0.5);
}

TEST(TerrainSynthetic, CengaloFaceAndGlacierHaveTheirAngles) {
  const DemRaster d = synth("kind = \"cengalo\"\ncell_size = 4\n");
  const double x0 = 2600000, y = 1200600; // trough axis
  EXPECT_NEAR(slopeAlongX(d, x0 + 100 + 200, y), 60, 0.5);
  EXPECT_NEAR(slopeAlongX(d, x0 + 500 + 350, y), 15, 0.5);
}

TEST(TerrainSynthetic, VajontDamClosesTheBasinAtItsHeight) {
  const DemRaster d = synth("kind = \"vajont\"\ncell_size = 5\n");
  const HeightField f(d);
  const double xc = 2600000 + 800, y0 = 1200000;
  const double basin = f.height(xc, y0 + 1100), gorge = f.height(xc, y0 + 1500);
  // Crest 180 m above the basin floor at the dam (floor inclined 0.5 deg over 200 m: 1.7 m).
  EXPECT_NEAR(f.height(xc, y0 + 1300) - f.height(xc, y0 + 1250), 180, 3);
  EXPECT_LT(gorge, basin - 50); // the gorge floor drops 60 m below the basin's
}

TEST(TerrainSynthetic, WhymperSecondTrackIsGentlerThanTheCouloir) {
  const DemRaster plain = synth("kind = \"whymper\"\ncell_size = 4\n");
  const DemRaster two = synth("kind = \"whymper\"\ncell_size = 4\nside_offset = 250\n");
  const double x0 = 2600000, couloir = 1200400, side = 1200150;
  // Couloir (150 + 300 + 60 m, then 200 m down it): 48 degrees, untouched by the second track.
  EXPECT_NEAR(slopeAlongX(two, x0 + 710, couloir), 48, 0.5);
  EXPECT_NEAR(HeightField(two).height(x0 + 710, couloir), HeightField(plain).height(x0 + 710, couloir), 0.01);
  // Second track: the same ice cliff, then the 35-degree ramp, then 12 degrees.
  EXPECT_NEAR(slopeAlongX(two, x0 + 480, side), 65, 1.0);
  EXPECT_NEAR(slopeAlongX(two, x0 + 800, side), 35, 0.5);
  EXPECT_NEAR(slopeAlongX(two, x0 + 1400, side), 12, 0.5);
  // Above the cliff both tracks are the same hanging glacier: its profile, with a cross-slope
  // centred on the dividing line (side_width / 2 + 40 m north of the second track's axis).
  const double divide = side + 80 + 40;
  EXPECT_NEAR(slopeAlongX(two, x0 + 300, divide), 32, 0.5);
  EXPECT_LT(HeightField(two).height(x0 + 300, divide), HeightField(two).height(x0 + 300, divide + 60));
  EXPECT_LT(HeightField(two).height(x0 + 300, divide), HeightField(two).height(x0 + 300, divide - 60));
  // Below it the second track stays higher than the couloir (a step separates them).
  EXPECT_GT(HeightField(two).height(x0 + 900, side), HeightField(two).height(x0 + 900, couloir) + 100);
}

TEST(TerrainSynthetic, ReservoirBehindTheVajontDamHoldsWater) {
  test::useTestTerrainCache();
  const std::string s = R"([simulation]
dx = 10
particles_per_cell = 1
end_time = 1
[terrain]
synthetic = { kind = "vajont", cell_size = 10 }
boundary = "slip"
[[materials]]
name = "water"
model = "elastic"
density = 1000
youngs_modulus = 1e6
[[bodies]]
name = "reservoir"
kind = "water"
material = "water"
level = 650
bounds = [2600000, 1200000, 2601600, 1201280]
)";
  const SceneSetup sc = loadSceneString(s, "vajont.toml");
  // Basin floor at 500 + (2000 - y) tan 0.5 deg; water 150 m deep at most, trapezoidal section:
  // the reservoir holds tens of millions of m3. Here only its order and consistency are checked.
  EXPECT_GT(sc.bodies[0].seededVolume, 2e7);
  EXPECT_LT(sc.bodies[0].seededVolume, 2e8);
  EXPECT_NEAR(sc.bodies[0].seededVolume, sc.bodies[0].geometricVolume, 0.02 * sc.bodies[0].geometricVolume);
}

TEST(TerrainSynthetic, ShippedSlopeValleySceneLoads) {
  test::useTestTerrainCache();
  // Coarser than shipped so the test stays fast; the seeding must still match the geometry.
  const SceneSetup s = loadSceneFile(std::string(TALUS_SOURCE_DIR) + "/data/scenes/slope_valley.toml",
                                     {"simulation.dx=4", "simulation.particles_per_cell=27"});
  ASSERT_EQ(s.bodies.size(), 2u);
  const BodyReport& slab = s.bodies[0];
  EXPECT_NEAR(slab.seededVolume, slab.geometricVolume, 0.02 * slab.geometricVolume);
  // 150 m x 300 m of 35-degree slope, 3 m normal to it: 45000 m2 / cos 35 * 3 m.
  EXPECT_NEAR(slab.geometricVolume, 45000 / std::cos(35 * M_PI / 180) * 3, 0.02 * 164800);
  EXPECT_GT(s.bodies[1].particles, 0u);
  EXPECT_TRUE(s.dem);
  EXPECT_GT(s.settings.origin.x(), 2.5e6); // the local frame is in use
}
