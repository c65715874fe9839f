// The shipped cascade scenes (data/scenes/*.toml, docs/scenes/*.md) load and run a few steps with
// every output they ask for, at a coarser grid so CI stays fast. tools/run_scenes.sh runs each to
// its end (not in CI). The Wolfsgruben scene reads ../shared and skips without it.
#include "io/run/run_driver.h"
#include "terrain_test_support.h"
#include "tools/analysis.h"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>

using namespace talus;
namespace fs = std::filesystem;

namespace {

std::string sceneFile(const std::string& name) { return std::string(TALUS_SOURCE_DIR) + "/data/scenes/" + name + ".toml"; }

struct Ran {
  std::string dir;
  size_t particles = 0;
  SeriesTable series;
};

/// Loads the scene with `overrides` (a coarser dx, a short end time), runs it and checks what
/// every run must leave behind.
Ran runShort(const std::string& name, std::vector<std::string> overrides) {
  test::useTestTerrainCache();
  Ran r;
  r.dir = test::tempDir("scene_" + name);
  SceneSetup s = loadSceneFile(sceneFile(name), overrides);
  for (const auto& g : s.groups) r.particles += g->size();
  EXPECT_GT(r.particles, 1000u) << name;
  for (const auto& b : s.bodies)
    if (b.kind != "fixed") {
      EXPECT_GT(b.particles, 0u) << name << ": body " << b.label << " seeded nothing";
    }
  RunOptions opt;
  opt.outDir = r.dir;
  opt.progress = false;
  const RunResult res = runScene(std::move(s), opt);
  EXPECT_TRUE(res.ok) << name << ": " << res.error;
  std::ifstream in(r.dir + "/summary.json");
  std::stringstream ss;
  ss << in.rdbuf();
  EXPECT_NE(ss.str().find("\"status\": \"completed\""), std::string::npos) << name;
  r.series = analysis::readSeries(r.dir + "/series.csv");
  EXPECT_GE(r.series.rows.size(), 2u) << name;
  for (const char* f : {"maps/deposit_thickness.tif", "maps/initial_thickness.tif", "maps/ground_elevation.tif",
                        "maps/max_flow_height_vertical.png", "plots/kinetic_energy.png"})
    EXPECT_TRUE(fs::exists(r.dir + "/" + f)) << name << ": " << f;
  return r;
}

bool hasColumn(const SeriesTable& t, const std::string& c) { return t.column(c) >= 0; }

} // namespace

TEST(Scenes, VajontRunsAFewSteps) {
  const Ran r = runShort("vajont", {"simulation.dx=12", "simulation.end_time=0.1"});
  for (const char* c : {"probe_speed_m_s_P0", "discharge_m3_s_dam_water", "max_water_surface_m",
                        "kinetic_energy_J_rock", "kinetic_energy_J_water"})
    EXPECT_TRUE(hasColumn(r.series, c)) << c;
  EXPECT_TRUE(fs::exists(r.dir + "/maps/water/max_flow_height_vertical.tif"));
  EXPECT_TRUE(fs::exists(r.dir + "/maps/rock/deposit_thickness.tif"));
}

TEST(Scenes, CengaloRunsAFewSteps) {
  const Ran r = runShort("cengalo", {"simulation.dx=10", "simulation.end_time=0.1"});
  for (const char* c : {"kinetic_energy_J_rock", "kinetic_energy_J_ice", "kinetic_energy_J_sediment"})
    EXPECT_TRUE(hasColumn(r.series, c)) << c;
  EXPECT_TRUE(fs::exists(r.dir + "/maps/ice/erosion_depth.tif"));
}

TEST(Scenes, FluelaRunsAFewSteps) {
  const Ran r = runShort("fluela", {"simulation.dx=6", "simulation.end_time=0.1"});
  EXPECT_TRUE(fs::exists(r.dir + "/maps/rock/deposit_thickness.tif"));
  EXPECT_TRUE(fs::exists(r.dir + "/maps/snow/initial_thickness.tif"));
}

TEST(Scenes, WhymperRunsAFewSteps) {
  const Ran r = runShort("whymper", {"simulation.dx=6", "simulation.end_time=0.1"});
  for (const char* c : {"front_m_couloir", "front_m_glacier"}) EXPECT_TRUE(hasColumn(r.series, c)) << c;
}

TEST(Scenes, WolfsgrubenRunsAFewSteps) {
  if (test::sharedDir().empty()) GTEST_SKIP() << "../shared (AvaFrame avaWog data) not found";
  const Ran r = runShort("wolfsgruben", {"simulation.dx=6", "simulation.end_time=0.1"});
  EXPECT_TRUE(hasColumn(r.series, "front_m_path_aimec"));
  // The maps lie on the DEM's grid, so they can be compared with the reference cell by cell.
  const std::string ref = test::sharedDir() +
                          "/data/avaframe_avaWog/reference_com1DFA_avaWogNullTest/relWog_005698a9de_C_L_null_dfa_pft.asc";
  const DemRaster sim = analysis::readRaster(r.dir + "/maps/max_flow_height_slope_normal.tif");
  const analysis::Comparison c = analysis::compare(analysis::resample(sim, analysis::readRaster(ref).grid),
                                                   analysis::readRaster(ref), 0.1);
  EXPECT_GT(c.ref.area, 1e5);
  EXPECT_GT(c.sim.area, 1e4); // the release itself, after a few steps
}

TEST(Scenes, WolfsgrubenFromItsAvaFrameFolderRunsAFewSteps) {
  if (test::sharedDir().empty()) GTEST_SKIP() << "../shared (AvaFrame avaWog data) not found";
  const Ran r = runShort("wolfsgruben_avaframe", {"simulation.end_time=0.2"});
  // The folder's DEM is ESRI ASCII: so are the peak files AvaFrame's tools read.
  size_t asc = 0;
  for (const auto& e : fs::directory_iterator(r.dir + "/peakFiles"))
    asc += e.path().extension() == ".asc" && e.path().filename().string().rfind("relWog_", 0) == 0;
  EXPECT_EQ(asc, 4u); // pft, pfv, ppr, pfd
}
