// AvaFrame peak files (io/output/peak_files): written from the hazard maps under AvaFrame's names,
// read back with GDAL, on the DEM's grid.
#include "io/output/peak_files.h"
#include "io/run/run_driver.h"
#include "io/scene/avaframe_scene.h"
#include "io/scene/scene.h"
#include "terrain_test_support.h"
#include "tools/analysis.h"

#include <cmath>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <regex>
#include <sstream>

using namespace talus;
namespace fs = std::filesystem;

namespace {

const char* kScene = R"(
[simulation]
dx = 8.0
end_time = 1.0
[terrain]
synthetic = { kind = "slope_valley", cell_size = 20.0 }
friction = 0.3
[domain]
walls = "open"
[[materials]]
name = "snow"
preset = "snow"
[[bodies]]
name = "slab"
kind = "release"
material = "snow"
bounds = [2600250.0, 1200350.0, 2600400.0, 1200450.0]
thickness = 3.0
[output]
maps = true
peak_files = true
peak_file_format = "both"
)";

std::string runScene(const std::string& name, const std::vector<std::string>& sets, SceneSetup* keep = nullptr) {
  test::useTestTerrainCache();
  SceneSetup s = loadSceneString(kScene, "peak.toml", sets);
  if (keep) {
    keep->dem = s.dem;
    keep->output = s.output;
  }
  RunOptions o;
  o.outDir = test::tempDir(name);
  o.progress = false;
  EXPECT_TRUE(runScene(std::move(s), o).ok);
  return o.outDir;
}

std::vector<std::string> peakFiles(const std::string& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir + "/peakFiles")) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

} // namespace

TEST(PeakFiles, NamedLaidOutAndValuedAsAvaFrameReadsThem) {
  SceneSetup s;
  const std::string dir = runScene("peak_files", {}, &s);
  const auto names = peakFiles(dir);
  // Four result types in two formats, plus the .prj of each ASCII grid.
  ASSERT_EQ(names.size(), 12u);
  const std::regex pattern("slab_([0-9a-f]{10})_C_L_null_mpm_(pft|pfv|ppr|pfd)\\.(asc|tif|prj)");
  std::string hash;
  for (const auto& n : names) {
    std::smatch m;
    ASSERT_TRUE(std::regex_match(n, m, pattern)) << n;
    if (hash.empty()) hash = m[1];
    EXPECT_EQ(m[1], hash) << "one simHash per run";
  }
  // Each is its hazard map, on the DEM's grid: ASCII keeps 9 significant digits (float32 exact
  // to rounding, 1e-6 relative); the GeoTIFF is bit-identical.
  const std::pair<const char*, const char*> pairs[] = {{"pft", "max_flow_height_slope_normal"},
                                                       {"pfv", "max_speed"},
                                                       {"ppr", "max_pressure"},
                                                       {"pfd", "max_flow_height_vertical"}};
  const RasterGrid& g = s.dem->grid;
  for (const auto& [type, map] : pairs) {
    const DemRaster ref = analysis::readRaster(dir + "/maps/" + map + ".tif");
    double peak = 0;
    for (const char* ext : {".asc", ".tif"}) {
      const std::string file = dir + "/peakFiles/slab_" + hash + "_C_L_null_mpm_" + type + ext;
      const DemRaster r = analysis::readRaster(file);
      EXPECT_EQ(r.grid.nx, g.nx) << file;
      EXPECT_EQ(r.grid.ny, g.ny) << file;
      EXPECT_NEAR(r.grid.originX, g.originX, 1e-6) << file;
      EXPECT_NEAR(r.grid.originY, g.originY, 1e-6) << file;
      EXPECT_NEAR(r.grid.cellSize, g.cellSize, 1e-9) << file;
      EXPECT_TRUE(sameCrs(r.grid.crsWkt, g.crsWkt) && !r.grid.crsWkt.empty()) << file;
      ASSERT_EQ(r.height.size(), ref.height.size());
      for (size_t i = 0; i < r.height.size(); ++i) {
        if (std::isnan(ref.height[i])) {
          EXPECT_TRUE(std::isnan(r.height[i]));
          continue;
        }
        EXPECT_NEAR(r.height[i], ref.height[i], 1e-6 * std::max(1.0f, std::abs(ref.height[i]))) << file << " cell " << i;
        peak = std::max(peak, double(r.height[i]));
      }
    }
    EXPECT_GT(peak, 0) << type << ": the map holds the release at least";
  }
  // The header AvaFrame writes: ncols, nrows, xllcorner (the west edge), cellsize, NODATA_value.
  std::ifstream asc(dir + "/peakFiles/slab_" + hash + "_C_L_null_mpm_pft.asc");
  std::string key;
  double v;
  asc >> key >> v;
  EXPECT_EQ(key, "ncols");
  EXPECT_EQ(v, g.nx);
  asc >> key >> v >> key >> v;
  EXPECT_EQ(key, "xllcorner");
  EXPECT_NEAR(v, g.originX, 1e-6);
}

TEST(PeakFiles, TheSimNameFollowsAvaFrameAndTheHashTheConfiguration) {
  PeakFileSettings p;
  p.releaseName = "rock slab";
  p.simHash = "0123456789";
  p.simType = "ent";
  // An underscore in the release name gets AvaFrame's "_AF", where its parser splits the name.
  EXPECT_EQ(avaFrameSimName(p), "rock_slab_AF_0123456789_C_L_ent_mpm");
  test::useTestTerrainCache();
  const auto hash = [](const std::vector<std::string>& sets) {
    return loadSceneString(kScene, "peak.toml", sets).output.maps.peakFiles.simHash;
  };
  EXPECT_EQ(hash({}), hash({}));
  EXPECT_NE(hash({}), hash({"terrain.friction=0.31"}));
  EXPECT_EQ(hash({}).size(), 10u);
}

TEST(PeakFiles, AnAvaFrameRunWritesOnTheDemGridInTheDemFormat) {
  if (test::sharedDir().empty()) GTEST_SKIP() << "../shared (AvaFrame avaWog data) not found";
  test::useTestTerrainCache();
  const std::string scene = R"(
[simulation]
dx = 12.0
end_time = 0.3
[terrain]
friction = 0.155
[[materials]]
name = "snow"
preset = "snow"
)";
  SceneSetup s = loadSceneString(scene, "wog.toml", {avaFrameOverride(test::sharedDir() + "/data/avaframe_avaWog")});
  RunOptions o;
  o.outDir = test::tempDir("peak_files_wog");
  o.progress = false;
  ASSERT_TRUE(runScene(std::move(s), o).ok);
  std::string pft;
  for (const auto& n : peakFiles(o.outDir))
    if (n.size() > 8 && n.substr(n.size() - 8) == "_pft.asc") pft = n;
  ASSERT_FALSE(pft.empty()) << "an .asc DEM gives .asc peak files";
  EXPECT_EQ(pft.rfind("relWog_", 0), 0u) << pft;
  // The DEM: 490 x 555 cells of 4.997678230579 m, xllcenter 167455.348391387.
  const DemRaster r = analysis::readRaster(o.outDir + "/peakFiles/" + pft);
  EXPECT_EQ(r.grid.nx, 490);
  EXPECT_EQ(r.grid.ny, 555);
  EXPECT_NEAR(r.grid.originX, 167455.348391387 - 4.997678230579 / 2, 1e-6);
  EXPECT_NEAR(r.grid.cellSize, 4.997678230579, 1e-9);
}

TEST(PeakFiles, TheMassLogAndConfigurationAreWhereAndAsAvaFrameReadsThem) {
  // com1DFA's mass_<simName>.txt (AIMEC's mass analysis: numpy.loadtxt, comma-separated, one
  // header row) and configurationFiles/<simName>.ini (cfgUtils: configparser, keys as written).
  SceneSetup s;
  const std::string dir = runScene("peak_files_mass", {"simulation.end_time=0.55"}, &s);
  const std::string simName = peakFiles(dir).front().substr(0, peakFiles(dir).front().rfind('_'));
  std::ifstream in(dir + "/mass_" + simName + ".txt");
  ASSERT_TRUE(in) << "mass_" << simName << ".txt";
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header, "time, current, entrained, detrained, detrainedTotal, stopped");
  std::vector<std::array<double, 6>> rows;
  for (std::string line; std::getline(in, line);) {
    std::array<double, 6> r{};
    ASSERT_EQ(std::sscanf(line.c_str(), "%lf, %lf, %lf, %lf, %lf, %lf", &r[0], &r[1], &r[2], &r[3], &r[4], &r[5]), 6) << line;
    rows.push_back(r);
  }
  // 0, 0.1 ... 0.5 s; the released mass throughout (nothing leaves the domain in 0.55 s), no
  // entrainment, no forest.
  SceneSetup seeded = loadSceneString(kScene, "peak.toml");
  double mass = 0;
  for (const auto& g : seeded.groups)
    for (Real m : g->particles.mass) mass += double(m);
  ASSERT_EQ(rows.size(), 6u);
  for (size_t k = 0; k < rows.size(); ++k) {
    EXPECT_NEAR(rows[k][0], 0.1 * double(k), 1e-9);
    EXPECT_NEAR(rows[k][1], mass, 1e-6 * mass) << "row " << k;
    for (int c = 2; c < 6; ++c) EXPECT_EQ(rows[k][c], 0.0) << "row " << k << " column " << c;
  }
  // Python's configparser (as AvaFrame's cfgUtils) and numpy.loadtxt (as AIMEC) read them, in
  // Debian's /usr/bin/python3 with python3-numpy (tools/setup.sh installs both).
  const std::string ini = dir + "/configurationFiles/" + simName + ".ini";
  ASSERT_TRUE(fs::exists(ini));
  const std::string py = "/usr/bin/python3 -c \"import configparser, numpy; c = configparser.ConfigParser(); c.optionxform = str; "
                         "c.read('" + ini + "'); m = numpy.loadtxt('" + dir + "/mass_" + simName +
                         ".txt', delimiter=',', skiprows=1); print(c['GENERAL']['mu'], c['GENERAL']['simTypeActual'], "
                         "c['TALUS']['bodies[0].thickness'], m.shape[0], m.shape[1])\" 2>&1";
  FILE* p = popen(py.c_str(), "r");
  ASSERT_NE(p, nullptr);
  char buf[512] = {};
  std::string out;
  while (fgets(buf, sizeof buf, p)) out += buf;
  ASSERT_EQ(pclose(p), 0) << out;
  EXPECT_EQ(out, "0.29999999999999999 null 3 6 6\n");
}

TEST(PeakFiles, Com1dfaGridIsTheMeshCom1dfaWritesAndValuesAreResampledOntoIt) {
  // avaWog's DEM (Inputs/avaWog.asc): 490 x 555 cells of 4.997678230579 m, lower-left centre
  // (167455.348391387, 361955.626633194). com1DFA's reference peak files
  // (reference_com1DFA_avaWogNullTest/*_ppr.asc): 489 x 554 of 5 m, xllcorner 167452.848391387,
  // yllcorner 361953.126633193984.
  RasterGrid dem;
  dem.nx = 490, dem.ny = 555, dem.cellSize = 4.997678230579;
  dem.originX = 167455.348391387 - 0.5 * dem.cellSize;
  dem.originY = 361955.626633194 - 0.5 * dem.cellSize + dem.ny * dem.cellSize;
  const RasterGrid g = com1dfaGrid(dem, 5.0);
  EXPECT_EQ(g.nx, 489);
  EXPECT_EQ(g.ny, 554);
  EXPECT_NEAR(g.originX, 167452.848391387, 1e-6);
  EXPECT_NEAR(g.originY - g.ny * g.cellSize, 361953.126633194, 1e-6);
  // A linear field is reproduced exactly (bilinear), no data spreads to the nearest centre only,
  // and centres beyond the source are NaN.
  std::vector<float> v(dem.size());
  for (int r = 0; r < dem.ny; ++r)
    for (int c = 0; c < dem.nx; ++c) v[dem.index(c, r)] = float(0.01 * (dem.cellCentreX(c) - 167000) + 0.02 * r);
  v[dem.index(100, 100)] = -9999;
  const std::vector<float> out = resampleCentres(dem, v, -9999, g);
  size_t nan = 0;
  for (int r = 0; r < g.ny; ++r)
    for (int c = 0; c < g.nx; ++c) {
      const float o = out[g.index(c, r)];
      if (std::isnan(o)) {
        ++nan;
        continue;
      }
      const double rowF = (dem.originY - g.cellCentreY(r)) / dem.cellSize - 0.5;
      const double expect = 0.01 * (g.cellCentreX(c) - 167000) + 0.02 * rowF;
      if (std::abs(c * 5.0 - 100 * dem.cellSize) > 10 || std::abs(rowF - 100) > 2) {
        EXPECT_NEAR(o, expect, 2e-4 * std::abs(expect)) << c << "," << r;
      }
    }
  // The mesh lies within the DEM's centres; of the mesh centres around the no-data cell, the one
  // nearest to it has no data, the others take their nearest centre's value.
  EXPECT_EQ(nan, 1u);
}
