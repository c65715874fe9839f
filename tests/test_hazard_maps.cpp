// Hazard maps: GeoTIFFs on the DEM's grid and CRS that gdalinfo reads, with values checked
// against a slab of known thickness moving at a known speed over a known slope.
#include "io/terrain/dem_raster.h"
#include "io/common/input_error.h"
#include "io/common/raster_reader.h"
#include "io/output/hazard_maps.h"
#include "io/run/run_driver.h"
#include "test_support.h"
#include "two_slabs.h"

#include <array>
#include <cairo.h>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

using namespace talus;
namespace fs = std::filesystem;

namespace {

std::string runCommand(const std::string& cmd, int& status) {
  std::string out;
  FILE* p = popen(cmd.c_str(), "r");
  if (!p) {
    status = -1;
    return out;
  }
  std::array<char, 4096> buf;
  size_t n;
  while ((n = fread(buf.data(), 1, buf.size(), p)) > 0) out.append(buf.data(), n);
  status = pclose(p);
  return out;
}

struct Raster {
  RasterGrid grid;
  std::vector<float> v;
  /// Value of the cell containing world (x, y).
  float at(double x, double y) const {
    int c = 0, r = 0;
    if (!grid.locate(x, y, c, r)) {
      ADD_FAILURE() << "outside the raster: " << x << ", " << y;
      return NAN;
    }
    return v[grid.index(c, r)];
  }
};

Raster readTif(const std::string& path) {
  Raster r;
  try {
    FloatRaster f = readFloatRaster(path, "a map");
    r.grid = f.grid;
    r.v = std::move(f.values);
  } catch (const InputError& e) {
    ADD_FAILURE() << e.what();
  }
  return r;
}

std::string fixed15(double v) {
  char b[64];
  std::snprintf(b, sizeof b, "%.15f", v);
  return b;
}

/// Every .tif under dir: gdalinfo reads it with the expected size, origin, pixel size, CRS and
/// nodata, and its band says what it holds. Returns how many were checked.
int checkWithGdalinfo(const std::string& dir, const RasterGrid& g, const std::string& crsId) {
  int checked = 0;
  int status = 0;
  runCommand("gdalinfo --version", status);
  if (status != 0) {
    ADD_FAILURE() << "gdalinfo not found (Debian package gdal-bin, installed by tools/setup.sh)";
    return 0;
  }
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (e.path().extension() != ".tif") continue;
    const std::string info = runCommand("gdalinfo '" + e.path().string() + "' 2>&1", status);
    EXPECT_EQ(status, 0) << info;
    int q = 0;
    while (q < HazardMaps::kQuantities && e.path().stem() != HazardMaps::stem(HazardMaps::Quantity(q))) ++q;
    if (q == HazardMaps::kQuantities) {
      ADD_FAILURE() << "unexpected map " << e.path();
      continue;
    }
    for (const std::string& s :
         {"Size is " + std::to_string(g.nx) + ", " + std::to_string(g.ny),
          "Origin = (" + fixed15(g.originX) + "," + fixed15(g.originY) + ")",
          "Pixel Size = (" + fixed15(g.cellSize) + "," + fixed15(-g.cellSize) + ")", crsId,
          std::string("NoData Value=-9999"), std::string("Description = ") + HazardMaps::band(HazardMaps::Quantity(q)),
          std::string("Unit Type: ") + HazardMaps::unit(HazardMaps::Quantity(q))})
      EXPECT_NE(info.find(s), std::string::npos) << e.path() << " lacks '" << s << "':\n" << info;
    ++checked;
  }
  return checked;
}

void expectPng(const std::string& path) {
  cairo_surface_t* img = cairo_image_surface_create_from_png(path.c_str());
  EXPECT_EQ(cairo_surface_status(img), CAIRO_STATUS_SUCCESS) << path;
  cairo_surface_destroy(img);
}


} // namespace

TEST(OutputMaps, GeoTiffsOnTheDemGridReadByGdalinfoMatchASlidingSlab) {
  const std::string dir = test::tempDir("maps_dem");
  SceneSetup scene = loadSceneString(test::kSlabs, "test.toml");
  auto dem = std::make_shared<DemRaster>();
  dem->grid.nx = 40, dem->grid.ny = 30, dem->grid.cellSize = 0.2;
  dem->grid.originX = 2599998.0, dem->grid.originY = 1200004.0; // larger than the domain
  dem->grid.crsWkt = crsToWkt("EPSG:2056");
  dem->height.resize(dem->grid.size());
  for (int r = 0; r < dem->grid.ny; ++r)
    for (int c = 0; c < dem->grid.nx; ++c)
      dem->height[dem->grid.index(c, r)] = float(999 + 0.5 * (dem->grid.cellCentreX(c) - 2599998.0));
  int hc, hr;
  ASSERT_TRUE(dem->grid.locate(2600003.7, 1200000.3, hc, hr));
  dem->height[dem->grid.index(hc, hr)] = NAN; // a hole in the DEM
  scene.dem = dem;
  RunOptions opt;
  opt.outDir = dir;
  opt.progress = false;
  ASSERT_TRUE(runScene(std::move(scene), opt).ok);

  // 8 maps for all material (with erosion, initial thickness and the ground), 6 for rock (not
  // erodible), 7 for snow.
  EXPECT_EQ(checkWithGdalinfo(dir + "/maps", dem->grid, "ID[\"EPSG\",2056]"), 21);
  EXPECT_FALSE(fs::exists(dir + "/maps/snow/ground_elevation.tif"));
  EXPECT_FALSE(fs::exists(dir + "/maps/ground_elevation.png"));
  for (const char* f : {"maps/erosion_depth.png", "maps/max_pressure.png", "maps/snow/max_speed.png"})
    expectPng(dir + "/" + f);
  EXPECT_FALSE(fs::exists(dir + "/maps/rock/erosion_depth.tif"));

  auto map = [&](const std::string& name) { return readTif(dir + "/maps/" + name + ".tif"); };
  const Raster hv = map("max_flow_height_vertical"), hn = map("max_flow_height_slope_normal"),
               speed = map("max_speed"), pressure = map("max_pressure"), deposit = map("deposit_thickness"),
               erosion = map("erosion_depth"), rockH = map("rock/max_flow_height_vertical"),
               snowErosion = map("snow/erosion_depth"), initial = map("initial_thickness"),
               snowInitial = map("snow/initial_thickness"), ground = map("ground_elevation");
  const double X = 2600000, Y = 1200000;
  // Cells whose centre is 0.3 m (a cell and a half particle spacing) inside a slab see exactly
  // its thickness: bilinear splatting of a regular lattice sums to one. Float storage: 1e-5.
  const double h = 0.4, cosSlope = 1 / std::sqrt(1.25), tol = 1e-5;
  EXPECT_NEAR(hv.at(X + 0.9, Y + 0.7), h, tol);                    // where the snow started
  EXPECT_NEAR(hv.at(X + 3.1, Y + 0.7), h, tol);                    // where it ended
  EXPECT_NEAR(hn.at(X + 0.9, Y + 0.7), h * cosSlope, tol);         // slope-normal on the DEM slope
  EXPECT_NEAR(speed.at(X + 2.1, Y + 0.7), 2.0, tol);               // its speed, and rho v^2 in kPa
  EXPECT_NEAR(pressure.at(X + 2.1, Y + 0.7), 300 * 4 / 1000.0, tol);
  EXPECT_NEAR(deposit.at(X + 0.9, Y + 0.7), 0.0, tol);             // vacated
  EXPECT_NEAR(deposit.at(X + 2.5, Y + 0.7), h, tol);               // covered at the end
  EXPECT_NEAR(erosion.at(X + 0.9, Y + 0.7), h, tol);               // lost all its snow
  EXPECT_NEAR(erosion.at(X + 2.1, Y + 0.7), 0.0, tol);             // covered before and after
  EXPECT_NEAR(snowErosion.at(X + 0.9, Y + 0.7), h, tol);
  EXPECT_NEAR(rockH.at(X + 3.3, Y + 2.1), h, tol);                 // the rock, at rest
  EXPECT_NEAR(rockH.at(X + 0.9, Y + 0.7), 0.0, tol);               // no rock where the snow was
  EXPECT_NEAR(speed.at(X + 3.3, Y + 2.1), 0.0, tol);
  EXPECT_NEAR(deposit.at(X + 3.3, Y + 2.1), h, tol);
  EXPECT_NEAR(erosion.at(X + 3.3, Y + 2.1), 0.0, tol);             // rock is not erodible
  EXPECT_NEAR(initial.at(X + 0.9, Y + 0.7), h, tol);               // the snow at the start
  EXPECT_NEAR(initial.at(X + 3.3, Y + 2.1), h, tol);               // the rock at the start
  EXPECT_NEAR(initial.at(X + 2.9, Y + 0.7), 0.0, tol);             // not yet reached
  EXPECT_NEAR(snowInitial.at(X + 3.3, Y + 2.1), 0.0, tol);
  EXPECT_NEAR(ground.at(X + 0.9, Y + 0.7), 999 + 0.5 * (X + 0.9 - 2599998.0), 1e-3); // the DEM itself
  // Speed is a mass-weighted mean, so every snow cell, even at the slab's fringe, reads 2 m/s.
  size_t snowCells = 0;
  for (size_t i = 0; i < speed.v.size(); ++i)
    if (speed.v[i] > 0) {
      EXPECT_NEAR(speed.v[i], 2.0, tol);
      ++snowCells;
    }
  EXPECT_GT(snowCells, 100u);
  // Outside the domain and in the DEM's hole: no data.
  EXPECT_EQ(hv.at(2599998.1, 1200003.9), -9999.f);
  EXPECT_EQ(hv.at(X + 3.7, Y + 0.3), -9999.f);
  EXPECT_EQ(hv.at(X + 3.7, Y + 0.5), 0.f);
}

namespace {

/// Rock blocks without gravity above a frictionless 30-degree plane in EPSG:2056, domain
/// 4 x `width` m, maps on 0.25 m cells; `blocks` are [[bodies]] tables, `maps` more map keys.
SceneSetup blocksOnAPlane(double width, const std::string& blocks, const std::string& maps) {
  return loadSceneString("[simulation]\ndx = 0.1\nend_time = 0.02\ngravity = [0, 0, 0]\n[domain]\n"
                         "min = [2600000, 1200000, 999]\nmax = [2600004, " + std::to_string(1200000 + width) +
                             ", 1005]\n[terrain]\nplane = { point = [2600000, 1200000, 1000], normal = [-0.5, 0, "
                             "0.8660254037844386] }\nboundary = \"slip\"\n[[materials]]\nname = \"rock\"\n"
                             "model = \"elastic\"\ndensity = 2500\nyoungs_modulus = 1e6\n" + blocks +
                             "[output]\ncrs = \"EPSG:2056\"\n[output.maps]\ncell_size = 0.25\nquicklook = false\n" + maps,
                         "test.toml");
}

const char* kBlock = "[[bodies]]\nmaterial = \"rock\"\nshape = \"box\"\nmin = [2600001, 1200000.5, 1003.2]\n"
                     "max = [2600003, 1200001.5, 1003.7]\n";

} // namespace

TEST(OutputMaps, WithoutDemTheGridCoversTheDomainAndTheSlopeComesFromTheTerrain) {
  const std::string dir = test::tempDir("maps_nodem");
  // A block resting (no gravity) above a 30-degree plane; maps on 0.25 m cells in EPSG:2056.
  SceneSetup scene = blocksOnAPlane(2, kBlock, "");
  RunOptions opt;
  opt.outDir = dir;
  opt.progress = false;
  ASSERT_TRUE(runScene(std::move(scene), opt).ok);
  RasterGrid g;
  g.nx = 16, g.ny = 8, g.cellSize = 0.25, g.originX = 2600000, g.originY = 1200002;
  EXPECT_EQ(checkWithGdalinfo(dir + "/maps", g, "ID[\"EPSG\",2056]"), 6); // no ground without a DEM
  EXPECT_FALSE(fs::exists(dir + "/maps/max_speed.png"));
  const Raster hv = readTif(dir + "/maps/max_flow_height_vertical.tif"),
               hn = readTif(dir + "/maps/max_flow_height_slope_normal.tif");
  // Cell centre (2600002.125, 1200001.125) is 0.375 m inside the block: exactly 0.5 m thick;
  // the slope from the terrain SDF (bisection, then central differences) is 30 degrees.
  EXPECT_NEAR(hv.at(2600002.125, 1200001.125), 0.5, 1e-5);
  EXPECT_NEAR(hn.at(2600002.125, 1200001.125), 0.5 * std::cos(M_PI / 6), 1e-5);
}

TEST(OutputMaps, MinSpeedLeavesRestingMaterialOutOfTheFlowMaps) {
  // Two blocks: one at rest, one gliding along the slope at 1 m/s. With min_speed = 0.5 m/s the
  // resting one is no flow (flow height 0), the gliding one is its 0.5 m; both are in the
  // deposit, which counts every particle.
  const std::string dir = test::tempDir("maps_min_speed");
  const std::string gliding = "[[bodies]]\nmaterial = \"rock\"\nshape = \"box\"\nmin = [2600001, 1200002.5, 1003.2]\n"
                              "max = [2600003, 1200003.5, 1003.7]\nvelocity = [0, 1, 0]\n";
  SceneSetup scene = blocksOnAPlane(4, kBlock + gliding, "min_speed = 0.5\n");
  RunOptions opt;
  opt.outDir = dir;
  opt.progress = false;
  ASSERT_TRUE(runScene(std::move(scene), opt).ok);
  const Raster hv = readTif(dir + "/maps/max_flow_height_vertical.tif"), dep = readTif(dir + "/maps/deposit_thickness.tif");
  EXPECT_EQ(hv.at(2600002.125, 1200001.125), 0.f);         // at rest
  EXPECT_NEAR(hv.at(2600002.125, 1200003.125), 0.5, 1e-5); // gliding: the cell is inside it throughout
  EXPECT_NEAR(dep.at(2600002.125, 1200001.125), 0.5, 1e-5);
}

TEST(OutputMaps, AccumulationIsBitIdenticalAtOneAndTwoThreads) {
  // Maps are summed in parallel; like the engine, they must not depend on the thread count.
  auto sim = test::makeSimulation(test::kSlabs, {"simulation.gravity=[0,0,-9.81]"});
  const auto maps1 = test::slabMaps(*sim, test::tempDir("maps_threads")), maps2 = test::slabMaps(*sim, test::tempDir("maps_threads"));
  HazardMaps &one = *maps1, &two = *maps2;
  auto with = [](int threads, auto&& f) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    f();
  };
  with(1, [&] { one.onStart(*sim); });
  with(2, [&] { two.onStart(*sim); });
  for (int i = 0; i < 20; ++i) {
    const double dt = sim->step();
    with(1, [&] { one.onStep(*sim, dt); });
    with(2, [&] { two.onStep(*sim, dt); });
  }
  EXPECT_EQ(one.accumulations(), 21u);
  for (int layer = 0; layer < 3; ++layer)
    for (int q = 0; q < HazardMaps::Deposit; ++q) {
      const auto a = one.raster(HazardMaps::Quantity(q), layer), b = two.raster(HazardMaps::Quantity(q), layer);
      EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size() * sizeof(float)), 0) << HazardMaps::stem(HazardMaps::Quantity(q));
      EXPECT_GT(*std::max_element(a.begin(), a.end()), 0.f);
    }
}

TEST(OutputMaps, ACoverThatOnlyCreptReadsNoErosionAndAStripTakenReadsItsDepth) {
  // Issue 40: a cover of particles that only crept (moved unevenly by fractions of a particle
  // spacing) changes its mass per map cell by a per cent or so; on Flüela that made a speckle of
  // 1 mm - 5 cm over half the "eroded" cells of a 4 m cover. min_erosion_fraction (2 %) leaves
  // it out; a strip taken away keeps its full depth. Here: a 0.4 m snow slab of kSlabs (no
  // gravity, nothing steps), its particles displaced along x by A sin(2 pi x / L) with A k = 1 %
  // (a 1 % strain, as the creep), and the particles of 1.2 < x < 1.8 m (local) given no mass.
  const auto sim = test::makeSimulation(test::kSlabs);
  RunContext run;
  run.origin = sim->settings().origin;
  run.domainMin = sim->settings().domain.min, run.domainMax = sim->settings().domain.max;
  const RasterGrid grid = HazardMaps::domainGrid(run, 0.2);
  auto erosionAfter = [&](double fraction, bool strip) {
    auto s = test::makeSimulation(test::kSlabs);
    MapSettings ms;
    ms.enabled = true;
    ms.quicklook = false;
    ms.erodible = {"snow"};
    ms.minErosionFraction = fraction;
    HazardMaps maps(test::tempDir("maps_creep"), grid, nullptr, ms);
    maps.onStart(*s);
    ParticleSet& P = s->groups()[0]->particles;
    const double L = 0.8, A = 0.01 * L / (2 * M_PI);
    for (size_t p = 0; p < P.size(); ++p) {
      const double x = P.x[p].x();
      P.x[p].x() = Real(x + A * std::sin(2 * M_PI * x / L));
      if (strip && x > 1.2 && x < 1.8) P.mass[p] = 0;
    }
    maps.onFinish(*s, true);
    return maps.raster(HazardMaps::Erosion);
  };
  // Cells wholly inside the slab (0.4-2.4 x 0.4-1.2 m local, the splat reaching one cell).
  auto cellsInside = [&](auto&& f) {
    for (int r = 0; r < grid.ny; ++r)
      for (int c = 0; c < grid.nx; ++c) {
        const double x = grid.cellCentreX(c) - run.origin.x(), y = grid.cellCentreY(r) - run.origin.y();
        if (x > 0.6 && x < 2.2 && y > 0.6 && y < 1.0) f(x, grid.index(c, r));
      }
  };
  const std::vector<float> raw = erosionAfter(0, false), kept = erosionAfter(0.02, false), taken = erosionAfter(0.02, true);
  float rawLargest = 0, keptLargest = 0;
  size_t cells = 0, stripCells = 0;
  cellsInside([&](double x, size_t i) {
    rawLargest = std::max(rawLargest, raw[i]), keptLargest = std::max(keptLargest, kept[i]);
    ++cells;
    // Inside the strip, a cell away from its edges by the splat's reach reads the slab's 0.4 m.
    // (The splat reaches a cell on each side: the cell centred 0.3 m inside the strip.)
    if (x > 1.39 && x < 1.61) {
      EXPECT_NEAR(taken[i], 0.4, 0.02) << x;
      ++stripCells;
    }
    if (x < 1.01 || x > 1.99) { EXPECT_EQ(taken[i], 0.f) << x; }
  });
  std::printf("  %zu cells: the creep reads up to %.4f m of erosion at fraction 0, %.4f m at 0.02\n", cells, rawLargest, keptLargest);
  ASSERT_GT(cells, 10u);
  EXPECT_GT(stripCells, 0u);
  EXPECT_GT(rawLargest, 0.001f) << "the creep must show without the threshold, or this test cannot fail";
  EXPECT_EQ(keptLargest, 0.f);
}
