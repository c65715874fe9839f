// A resting uniform cover gives a uniform map (issue 40): the thickness maps of a layer seeded on
// a flat and on a sloping DEM vary from cell to cell by under 2 %, with no bands where the
// particle lattice and the map grid beat against each other.
#include "io/common/raster_reader.h"
#include "io/run/run_driver.h"
#include "io/terrain/terrain_loader.h"
#include "terrain_test_support.h"
#include "test_support.h"

#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>

using namespace talus;

namespace {

constexpr double kX0 = 2600000, kY0 = 1200000;

/// initial_thickness.tif of a run of a 2 m layer (vertical) over [20, 80] m of a 100 m square DEM
/// with 2 m cells sloping at `degrees` along x, dx 1 m; its cells 6 m or more inside the layer.
std::vector<float> coverMap(double degrees, const std::string& name, double jitter = 0.5) {
  test::useTestTerrainCache();
  const std::string dir = test::tempDir(name);
  const double tilt = std::tan(degrees * M_PI / 180);
  writeDemGeoTiff(test::makeDem(50, 50, 2, kX0, kY0, [&](double x, double) { return 1000 + tilt * (x - kX0); }),
                  dir + "/dem.tif");
  char bounds[160];
  std::snprintf(bounds, sizeof bounds, "[%.1f, %.1f, %.1f, %.1f]", kX0 + 20, kY0 + 20, kX0 + 80, kY0 + 80);
  const std::string text = "[simulation]\njitter = " + std::to_string(jitter) + "\ndx = 1\nend_time = 0.001\ngravity = [0, 0, 0]\n[terrain]\ndem = \"" + dir +
                           "/dem.tif\"\nboundary = \"sticky\"\n[[materials]]\nname = \"snow\"\nmodel = \"elastic\"\n"
                           "density = 300\nyoungs_modulus = 1e6\n[[bodies]]\nkind = \"layer\"\nmaterial = \"snow\"\n"
                           "thickness = 2\nthickness_direction = \"vertical\"\nfield_below = 0\nbounds = " +
                           std::string(bounds) + "\n[output]\nanimation = false\nreport = false\n[output.maps]\nquicklook = false\n";
  RunOptions opt;
  opt.outDir = dir;
  opt.progress = false;
  if (!runScene(loadSceneString(text, name + ".toml"), opt).ok) ADD_FAILURE() << "run failed";
  const FloatRaster map = readFloatRaster(dir + "/maps/initial_thickness.tif", "the initial thickness map");
  const int nx = map.grid.nx, ny = map.grid.ny;
  const std::vector<float>& v = map.values;
  std::vector<float> inside;
  const double gt[6] = {map.grid.originX, map.grid.cellSize, 0, map.grid.originY, 0, -map.grid.cellSize};
  for (int r = 0; r < ny; ++r)
    for (int c = 0; c < nx; ++c) {
      const double x = gt[0] + (c + 0.5) * gt[1] - kX0, y = gt[3] - (r + 0.5) * gt[1] - kY0;
      if (x > 26 && x < 74 && y > 26 && y < 74) inside.push_back(v[size_t(r) * nx + c]);
    }
  return inside;
}

/// Largest relative deviation of a cell from the mean.
double spread(const std::vector<float>& v) {
  double m = 0, worst = 0;
  for (float x : v) m += x;
  m /= double(v.size());
  for (float x : v) worst = std::max(worst, std::abs(x / m - 1));
  std::printf("  %zu cells, mean %.4f m, largest deviation %.2f %%\n", v.size(), m, 100 * worst);
  return worst;
}

} // namespace

TEST(MapUniformity, ALatticeCoverGivesAFlatMapOnFlatAndSlopingGround) {
  // Without the seeding's jitter the splat itself is exact: a 2 m cover on a lattice reads 2 m in
  // every map cell, flat or on a 30-degree slope (no bands where lattice and map grid beat).
  EXPECT_LT(spread(coverMap(0, "uniform_flat_lattice", 0)), 1e-4);
  EXPECT_LT(spread(coverMap(30, "uniform_slope_lattice", 0)), 1e-4);
}

TEST(MapUniformity, JitteredCoversGiveAFlatMapToo) {
  // Terrain bodies are seeded with jitter 0.5 by default (a lattice cut by a sloping surface
  // leaves terraces), along z only and decided by the lattice point, so every lattice column keeps
  // its particles (io/scene/particle_seeding.cpp). Issue 40's goal: under 2 % from cell to cell at
  // the default map cell. Measured 0.00 % flat and on the 30-degree slope; with the jitter in all
  // three axes it was 2.18 % and 5.82 % (4.10 % at jitter 0.25), which these bounds fail.
  EXPECT_LT(spread(coverMap(0, "uniform_flat")), 0.02);
  EXPECT_LT(spread(coverMap(30, "uniform_slope")), 0.02);
  EXPECT_LT(spread(coverMap(30, "uniform_slope_quarter", 0.25)), 0.02);
}
