// Wave gauges ([[output.gauges]]): still water reads its own level, over the floor and over a
// step under it; a dry gauge reads nothing; the column reads the depth wherever its bottom lies;
// a scene without water is refused by name.
#include "io/run/run_driver.h"
#include "io/output/water_gauges.h"
#include "test_support.h"

#include <cmath>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>

using namespace talus;

namespace {

const char* kTank = R"([simulation]
dx = 0.05
end_time = 0.02
[domain]
min = [100, 0, 50]
max = [103, 1, 51]
[[materials]]
name = "lake"
model = "water"
density = 1000
sound_speed = 20
[[bodies]]
material = "lake"
shape = "box"
min = [100, 0, 50]
max = [102, 1, 50.4]
[[structures]]
name = "step"
shape = "box"
min = [101.2, -1, 49]
max = [102.5, 2, 50.2]
[output]
series_interval = 0.01
h5 = false
vdb = false
plots = false
[[output.gauges]]
name = "floor"
point = [100.5, 0.5]
[[output.gauges]]
name = "step"
point = [101.6, 0.5]
[[output.gauges]]
name = "dry"
point = [102.75, 0.5]
)";

std::vector<std::vector<std::string>> readRows(const std::string& path) {
  std::vector<std::vector<std::string>> rows;
  std::ifstream in(path);
  for (std::string line; std::getline(in, line);) {
    std::stringstream s(line);
    rows.emplace_back();
    for (std::string f; std::getline(s, f, ',');) rows.back().push_back(f);
  }
  return rows;
}

} // namespace

TEST(WaterGauges, StillWaterReadsItsLevelOverTheFloorAndOverAStepAndADryGaugeReadsNothing) {
  const std::string dir = test::tempDir("gauges_still");
  RunOptions opt;
  opt.outDir = dir;
  opt.progress = false;
  ASSERT_TRUE(runScene(loadSceneString(kTank, "tank.toml"), opt).ok);
  const auto rows = readRows(dir + "/series.csv");
  ASSERT_GE(rows.size(), 3u);
  auto col = [&](const std::string& name) {
    for (size_t i = 0; i < rows[0].size(); ++i)
      if (rows[0][i] == name) return i;
    ADD_FAILURE() << "no column " << name;
    return size_t(0);
  };
  const size_t floor = col("water_surface_m_floor"), step = col("water_surface_m_step"), dry = col("water_surface_m_dry");
  // The level is 50.4 m (world z, the domain 50 m up) over the floor and over the step, which
  // leaves 0.2 m of water: the gauge reads the surface, not the depth. Seeded on a lattice whose
  // spacing (dx/2) divides the footprint, the tent-weighted volume is the depth exactly, so the
  // tolerance is float rounding of positions at 50 m (1e-5) at the start, and after 0.02 s the
  // settling of a Tait water at c = 20 m/s under its own weight (rho g d / (rho c^2) d = 4 mm
  // at most, seen as its volume at the reference density).
  EXPECT_NEAR(std::stod(rows[1][floor]), 50.4, 1e-4);
  EXPECT_NEAR(std::stod(rows[1][step]), 50.4, 1e-4);
  EXPECT_NEAR(std::stod(rows.back()[floor]), 50.4, 4e-3);
  EXPECT_NEAR(std::stod(rows.back()[step]), 50.4, 4e-3);
  EXPECT_EQ(rows[1][dry], "nan");
}

TEST(WaterGauges, AGaugeInASceneWithoutWaterIsRefusedByName) {
  std::string scene = kTank;
  scene.replace(scene.find("model = \"water\""), 15, "model = \"elastic\"");
  scene.replace(scene.find("sound_speed = 20"), 16, "youngs_modulus = 1e6");
  RunOptions opt;
  opt.outDir = test::tempDir("gauges_dry_scene");
  opt.progress = false;
  try {
    runScene(loadSceneString(scene, "tank.toml"), opt);
    FAIL() << "a gauge without water ran";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("gauge 'floor'"), std::string::npos) << e.what();
  }
}

// The column (WaterGauges::depths, what a jet thrown over a gauge adds as its thickness, not its
// elevation): the same tank at the start reads 0.4 m over the floor, 0.2 m over the step (its
// surface 50.4 m less its bottom 50.2 m) and 0 where dry; exact on the seeding lattice up to
// float rounding of positions at 50 m.
TEST(WaterGauges, TheColumnIsTheWatersDepthWhereverItsBottomLies) {
  SceneSetup s = loadSceneString(kTank, "tank.toml");
  const std::vector<GaugeSpec> gauges = s.output.gauges;
  Simulation sim(s.settings, std::move(s.groups));
  WaterGauges reader(gauges, {}, 0.025);
  reader.onStart(sim);
  const std::vector<double> depth = reader.depths(sim), surface = reader.surfaces(sim);
  ASSERT_EQ(depth.size(), 3u);
  EXPECT_NEAR(depth[0], 0.4, 1e-5);
  EXPECT_NEAR(depth[1], 0.2, 1e-5);
  EXPECT_EQ(depth[2], 0.0);
  EXPECT_NEAR(surface[1] - depth[1], 50.2, 1e-4);
}
