// DEM -> level set: true distances in the band, voxels on the simulation's grid nodes, the zero
// level through the DEM's cell-centre elevations, metadata, and the scene's level-set cache.
#include "io/terrain/vdb_level_set.h"
#include "io/terrain/dem_level_set.h"
#include "io/terrain/terrain_loader.h"
#include "terrain_test_support.h"

#include <algorithm>
#include <filesystem>
#include <functional>
#include <cmath>
#include <cstring>
#include <gtest/gtest.h>
#include <random>

using namespace talus;

namespace {

LevelSetBuildOptions optionsFor(const HeightField& f, double dx, const Vec3d& origin) {
  LevelSetBuildOptions o;
  o.dx = dx;
  o.origin = origin;
  o.xmin = f.xmin(), o.ymin = f.ymin(), o.xmax = f.xmax(), o.ymax = f.ymax();
  return o;
}

/// Distance from p to triangle abc (Ericson, Real-Time Collision Detection, 5.1.5).
double pointTriangle(const Vec3d& p, const Vec3d& a, const Vec3d& b, const Vec3d& c) {
  const Vec3d ab = b - a, ac = c - a, ap = p - a;
  const double d1 = ab.dot(ap), d2 = ac.dot(ap);
  if (d1 <= 0 && d2 <= 0) return (p - a).norm();
  const Vec3d bp = p - b;
  const double d3 = ab.dot(bp), d4 = ac.dot(bp);
  if (d3 >= 0 && d4 <= d3) return (p - b).norm();
  const double vc = d1 * d4 - d3 * d2;
  if (vc <= 0 && d1 >= 0 && d3 <= 0) return (p - (a + d1 / (d1 - d3) * ab)).norm();
  const Vec3d cp = p - c;
  const double d5 = ab.dot(cp), d6 = ac.dot(cp);
  if (d6 >= 0 && d5 <= d6) return (p - c).norm();
  const double vb = d5 * d2 - d1 * d6;
  if (vb <= 0 && d2 >= 0 && d6 <= 0) return (p - (a + d2 / (d2 - d6) * ac)).norm();
  const double va = d3 * d6 - d5 * d4;
  if (va <= 0 && (d4 - d3) >= 0 && (d5 - d6) >= 0)
    return (p - (b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b))).norm();
  const double denom = 1 / (va + vb + vc);
  return (p - (a + ab * vb * denom + ac * vc * denom)).norm();
}

/// Brute-force distance to the bilinear surface: every DEM patch within reach, each cut into
/// 8 x 8 squares of two triangles (the triangulation departs from the bilinear patch by at
/// most |h_uv| / (4 * 8^2) per patch, 1e-3 m = 5e-4 dx on the test surface below).
double bruteForceDistance(const HeightField& f, const Vec3d& p) {
  const RasterGrid& g = f.grid();
  const double reach = std::fabs(p.z() - f.height(p.x(), p.y())) + g.cellSize;
  double best = INFINITY;
  const int n = 8;
  const double step = g.cellSize / n;
  const int c0 = int(std::floor((p.x() - reach - g.originX) / g.cellSize - 0.5));
  const int c1 = int(std::ceil((p.x() + reach - g.originX) / g.cellSize - 0.5));
  const int r0 = int(std::floor((g.originY - p.y() - reach) / g.cellSize - 0.5));
  const int r1 = int(std::ceil((g.originY - p.y() + reach) / g.cellSize - 0.5));
  for (int c = c0; c < c1; ++c)
    for (int r = r0; r < r1; ++r) {
      const double x0 = g.cellCentreX(c), y0 = g.cellCentreY(r + 1); // patch's south-west corner
      for (int a = 0; a < n; ++a)
        for (int b = 0; b < n; ++b) {
          auto P = [&](int i, int j) {
            const double x = x0 + (a + i) * step, y = y0 + (b + j) * step;
            return Vec3d(x, y, f.height(x, y));
          };
          const Vec3d p00 = P(0, 0), p10 = P(1, 0), p01 = P(0, 1), p11 = P(1, 1);
          best = std::min({best, pointTriangle(p, p00, p10, p11), pointTriangle(p, p00, p11, p01)});
        }
    }
  return best;
}

} // namespace

TEST(TerrainLevelSet, TiltedPlaneHoldsTheAnalyticDistanceInTheBand) {
  const std::string dir = test::tempDir("ls_plane");
  const double gx = 0.4, gy = -0.35, x0 = 2600000, y0 = 1200000, cell = 2;
  auto h = [&](double x, double y) { return 1000 + gx * (x - x0) + gy * (y - y0); };
  const DemRaster dem = test::makeDem(80, 60, cell, x0, y0, h);
  const HeightField f(dem);
  const double dx = 1.5;
  const Vec3d origin(x0 + 0.3, y0 + 0.7, 950.2); // voxels deliberately off the DEM's cells
  buildDemLevelSet(f, optionsFor(f, dx, origin), dir + "/plane.vdb");
  const VdbLevelSet ls(dir + "/plane.vdb", "", origin);
  EXPECT_NEAR(ls.voxelSize(), dx, 1e-12);
  EXPECT_TRUE(sameCrs(ls.metadata("crs_wkt"), dem.grid.crsWkt));
  const double norm = std::sqrt(1 + gx * gx + gy * gy);
  std::mt19937 rng(7);
  // Between nodes the trilinear stencil reaches ~1.7 dx further out: stay clear of the band edge.
  std::uniform_real_distribution<double> ux(x0 + 12, x0 + 148), uy(y0 + 12, y0 + 108), uphi(-2.5 * dx, 2.5 * dx),
      uoff(-1.2 * dx, 1.2 * dx);
  double maxNode = 0, maxOff = 0;
  int n = 0;
  for (int s = 0; s < 4000; ++s) {
    // At grid nodes (what the engine samples) and at arbitrary points (trilinear in between).
    const double x = ux(rng), y = uy(rng), phi = uphi(rng), off = uoff(rng);
    const Vec3d local = Vec3d(x - gx * phi / norm, y - gy * phi / norm, h(x, y) + phi / norm) - origin;
    const Vec3d node = (local / dx).array().round().matrix() * dx;
    const double exactNode = (origin.z() + node.z() - h(origin.x() + node.x(), origin.y() + node.y())) / norm;
    if (std::fabs(exactNode) < 2.5 * dx) maxNode = std::max(maxNode, std::fabs(ls.distance(node) - exactNode)), ++n;
    const Vec3d between = Vec3d(x - gx * off / norm, y - gy * off / norm, h(x, y) + off / norm) - origin;
    maxOff = std::max(maxOff, std::fabs(ls.distance(between) - off));
  }
  EXPECT_GT(n, 2000);
  // The issue's bound: 0.05 dx. Both are exact up to float storage (~1e-4 m at phi ~ 4 m).
  EXPECT_LT(maxNode, 0.05 * dx);
  EXPECT_LT(maxOff, 0.05 * dx);
  std::printf("[ measured ] plane: max |phi - exact| %.2e dx at nodes, %.2e dx between\n", maxNode / dx, maxOff / dx);
}

TEST(TerrainLevelSet, CurvedTerrainMatchesBruteForceDistance) {
  // Slopes up to 57 degrees and curvature radii down to 25 m (12 voxels): closest-point
  // distances stay exact, the slope-corrected vertical difference does not.
  const std::string dir = test::tempDir("ls_curved");
  const double x0 = 2600000, y0 = 1200000, cell = 2;
  auto h = [&](double x, double y) {
    return 1200 + 50 * std::sin(2 * M_PI * (x - x0) / 200) * std::cos(2 * M_PI * (y - y0) / 160);
  };
  const DemRaster dem = test::makeDem(100, 100, cell, x0, y0, h);
  const HeightField f(dem);
  const double dx = 2;
  const Vec3d origin(x0 + 1, y0 + 1, 1000); // voxel columns on the cell centres
  auto o = optionsFor(f, dx, origin);
  buildDemLevelSet(f, o, dir + "/cp.vdb");
  o.closestPoint = false;
  buildDemLevelSet(f, o, dir + "/vert.vdb");
  const VdbLevelSet cp(dir + "/cp.vdb", "", origin), vert(dir + "/vert.vdb", "", origin);
  std::mt19937 rng(11);
  std::uniform_int_distribution<int> ui(10, 89), uk(-3, 3);
  double errCp = 0, errVert = 0;
  int n = 0;
  while (n < 800) {
    const int i = ui(rng), j = ui(rng);
    const double x = origin.x() + i * dx, y = origin.y() + j * dx;
    const int k = int(std::lround((f.height(x, y) - origin.z()) / dx)) + uk(rng);
    const Vec3d local(i * dx, j * dx, k * dx);
    const double exact = std::copysign(bruteForceDistance(f, origin + local), origin.z() + local.z() - f.height(x, y));
    if (std::fabs(exact) >= 2.5 * dx) continue; // inside the band (3 dx), away from its clamp
    errCp = std::max(errCp, std::fabs(cp.distance(local) - exact));
    errVert = std::max(errVert, std::fabs(vert.distance(local) - exact));
    ++n;
  }
  std::printf("[ measured ] curved: max error closest-point %.4f dx, vertical difference %.4f dx\n", errCp / dx,
              errVert / dx);
  EXPECT_LT(errCp, 0.05 * dx);
}

// The terrain cache is read on demand (VdbLoading::OnDemand): the same values as a whole read,
// bit for bit, with only the leaves a process samples in memory, so a rank whose blocks cover
// a corner of the terrain holds about that corner's values, not the whole level set.
TEST(TerrainLevelSet, OnDemandReadsTheSameValuesAndHoldsOnlyTheLeavesItSamples) {
  const std::string dir = test::tempDir("ls_on_demand");
  const double x0 = 2600000, y0 = 1200000, cell = 2;
  auto h = [&](double x, double y) { return 1200 + 0.3 * (x - x0) + 20 * std::sin((y - y0) / 40); };
  const DemRaster dem = test::makeDem(600, 600, cell, x0, y0, h);
  const HeightField f(dem);
  const double dx = 2;
  const Vec3d origin(x0 + 1, y0 + 1, 1000);
  buildDemLevelSet(f, optionsFor(f, dx, origin), dir + "/t.vdb");
  const VdbLevelSet whole(dir + "/t.vdb", "", origin), lazy(dir + "/t.vdb", "", origin, VdbLoading::OnDemand);
  const double wholeBytes = double(whole.residentBytes()), layout = double(lazy.residentBytes());
  // The layout alone: about 150 bytes per leaf of 2 KB values, and the internal nodes (33 KB per
  // 128-voxel cube holding leaves, 270 KB per 1024-voxel cube): 13 % of the whole here, 15 % on
  // Wolfsgruben at dx 2.5 m. Read whole, it would be 100 %.
  EXPECT_LT(layout, 0.2 * wholeBytes) << "an on-demand level set read its values up front";
  // A corner: blocks 0..3 in x and y (64 m of the 1 200 m square), down the terrain's column there.
  int sampled = 0;
  for (int bx = 0; bx < 4; ++bx)
    for (int by = 0; by < 4; ++by)
      for (int bz = 0; bz < 30; ++bz) {
        SdfBlock a{}, b{};
        const BlockCoord c{bx, by, bz};
        const bool ga = whole.sampleBlock(c, dx, a), gb = lazy.sampleBlock(c, dx, b);
        ASSERT_EQ(ga, gb);
        ASSERT_EQ(std::memcmp(&a, &b, sizeof a), 0) << "block " << bx << " " << by << " " << bz;
        sampled += ga;
      }
  ASSERT_GT(sampled, 0) << "the corner's blocks hold no ground: the test would compare nothing";
  EXPECT_EQ(whole.distance(Vec3d(123.4, 56.7, 250)), lazy.distance(Vec3d(123.4, 56.7, 250)));
  const double held = double(lazy.residentBytes());
  std::printf("[ measured ] on demand: layout %.2f MB, after a corner %.2f MB, whole %.2f MB\n", layout / 1e6,
              held / 1e6, wholeBytes / 1e6);
  EXPECT_GT(held, layout) << "sampling loaded no leaf: residentBytes does not count what it reads";
  // The corner is 1/350 of the square's area; its leaves (with their neighbours for the
  // normals and the interpolation) stay well under a twentieth of the values.
  EXPECT_LT(held - layout, 0.05 * (wholeBytes - layout));

  // focus(): the layout too, only around the blocks (a rank's part), read again as they move.
  auto sameBlocks = [&](int x0, int y0) {
    for (int bx = x0; bx < x0 + 2; ++bx)
      for (int by = y0; by < y0 + 2; ++by)
        for (int bz = 0; bz < 30; ++bz) {
          SdfBlock a{}, b{};
          const BlockCoord c{bx, by, bz};
          const bool ga = whole.sampleBlock(c, dx, a), gb = lazy.sampleBlock(c, dx, b);
          if (ga != gb || std::memcmp(&a, &b, sizeof a) != 0) return false;
        }
    return true;
  };
  lazy.focus({0, 0, 0}, {1, 1, 29}, dx);
  EXPECT_TRUE(sameBlocks(0, 0));
  const double corner = double(lazy.residentBytes());
  // Kept: the blocks and 4 around them (12 x 12 of 75 x 75 blocks), in one 1024-voxel node
  // (270 KB) and a few 128-voxel ones; measured 0.67 MB against the whole layout's 3.9 MB.
  EXPECT_LT(corner, 0.25 * layout) << "focus kept the whole layout";
  EXPECT_THROW(lazy.distance(Vec3d(380, 380, 250)), std::logic_error) << "a query outside answered silently";
  lazy.focus({20, 20, 0}, {21, 21, 29}, dx); // the far corner: read again there
  EXPECT_TRUE(sameBlocks(20, 20));
  EXPECT_EQ(whole.distance(Vec3d(340, 340, 250)), lazy.distance(Vec3d(340, 340, 250)));
  EXPECT_THROW(lazy.distance(Vec3d(10, 10, 250)), std::logic_error);
  std::printf("[ measured ] focused on 2 x 2 blocks of 75 x 75: %.2f MB\n", corner / 1e6);

  // The cache cleared during a run: the next read names the file instead of crashing.
  std::filesystem::copy_file(dir + "/t.vdb", dir + "/gone.vdb");
  const VdbLevelSet gone(dir + "/gone.vdb", "", origin, VdbLoading::OnDemand);
  std::filesystem::remove(dir + "/gone.vdb");
  try {
    gone.focus({0, 0, 0}, {1, 1, 29}, dx);
    ADD_FAILURE() << "a removed file was read again";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("gone.vdb"), std::string::npos) << e.what();
  }
}

TEST(TerrainLevelSet, SignIsRightFarBelowAndAboveTheBand) {
  // Rolling terrain and a 75-degree cliff, whose leaves can lie wholly beyond the band.
  const std::string dir = test::tempDir("ls_sign");
  const double x0 = 2600000, y0 = 1200000;
  auto rolling = [&](double x, double y) { return 1500 + 0.8 * (x - x0) + 30 * std::sin((y - y0) / 40); };
  auto cliff = [&](double x, double y) {
    return 1500 + 3.73 * std::clamp(x - x0 - 80, 0.0, 80.0) + 10 * std::sin((y - y0) / 25);
  };
  for (const auto& h : {std::function<double(double, double)>(rolling), std::function<double(double, double)>(cliff)}) {
    const DemRaster dem = test::makeDem(120, 90, 2, x0, y0, h);
    const HeightField f(dem);
    const Vec3d origin(x0, y0, 1400);
    buildDemLevelSet(f, optionsFor(f, 2, origin), dir + "/s.vdb");
    const VdbLevelSet ls(dir + "/s.vdb", "", origin);
    for (int i = 2; i < 118; i += 3)
      for (int j = 2; j < 88; j += 3) {
        const double x = x0 + i * 2 + 0.3, y = y0 + j * 2 + 0.7, z = f.height(x, y);
        for (double d : {10.0, 25.0, 40.0, 150.0}) {
          ASSERT_LT(ls.distance(Vec3d(x, y, z - d) - origin), 0) << i << " " << j << " " << d;
          ASSERT_GT(ls.distance(Vec3d(x, y, z + d) - origin), 0) << i << " " << j << " " << d;
        }
      }
  }
}

TEST(TerrainLevelSet, AvaWogZeroLevelPassesThroughTheCellCentreElevations) {
  if (test::sharedDir().empty()) GTEST_SKIP() << "../shared (AvaFrame test data) not present";
  test::useTestTerrainCache();
  const std::string asc = test::sharedDir() + "/data/avaframe_avaWog/Inputs/avaWog.asc";
  const DemRaster raw = readDem(asc, [] { DemReadOptions o; o.keepNodata = true; return o; }());
  const RasterGrid& g = raw.grid;
  // The domain's corner on a cell centre puts the level set's voxel columns on the centres.
  char scene[2048];
  std::snprintf(scene, sizeof scene, R"([simulation]
dx = %.17g
end_time = 1
[terrain]
dem = "%s"
fill_nodata = true
crs = "EPSG:31287"
boundary = "slip"
[domain]
min = [%.17g, %.17g, 1200]
max = [%.17g, %.17g, 2800]
[[materials]]
name = "snow"
model = "elastic"
density = 300
youngs_modulus = 1e6
[[bodies]]
material = "snow"
shape = "sphere"
center = [168500, 363300, 2700]
radius = 12
)",
                g.cellSize, asc.c_str(), g.cellCentreX(0), g.cellCentreY(g.ny - 1), g.cellCentreX(g.nx - 1),
                g.cellCentreY(0));
  const SceneSetup s = loadSceneString(scene, "wog.toml");
  ASSERT_TRUE(s.dem);
  EXPECT_NE(crsName(s.dem->grid.crsWkt).find("31287"), std::string::npos);
  const double dx = s.settings.dx;
  double worst = 0;
  size_t n = 0;
  for (int r = 0; r < g.ny; ++r)
    for (int c = 0; c < g.nx; ++c) {
      const float hc = raw.height[g.index(c, r)];
      if (std::isnan(hc)) continue; // filled cells are not data
      const Vec3d w(g.cellCentreX(c), g.cellCentreY(r), hc);
      const double e = std::fabs(s.settings.terrain->distance(w - s.settings.origin));
      worst = std::max(worst, e);
      ++n;
    }
  EXPECT_EQ(n, g.size() - 94079);
  std::printf("[ measured ] avaWog: max |phi| at %zu cell-centre elevations %.4f dx\n", n, worst / dx);
  EXPECT_LT(worst, 0.05 * dx);
}

TEST(TerrainLevelSet, SceneBuildsTheLevelSetOnceAndReusesItFromTheCache) {
  const std::string cache = test::tempDir("ls_cache");
  const char* before = std::getenv("TALUS_CACHE_DIR");
  const std::string saved = before ? before : "";
  setenv("TALUS_CACHE_DIR", cache.c_str(), 1);
  const std::string scene = R"([simulation]
dx = 5
end_time = 1
[terrain]
synthetic = { kind = "slope_valley", cell_size = 10 }
boundary = "slip"
[[materials]]
name = "snow"
model = "elastic"
density = 300
youngs_modulus = 1e6
[[bodies]]
kind = "layer"
material = "snow"
thickness = 2
bounds = [2600900, 1200100, 2601300, 1200300]
)";
  const SceneSetup a = loadSceneString(scene, "cache.toml");
  const SceneSetup b = loadSceneString(scene, "cache.toml");
  const SceneSetup c = loadSceneString(scene, "cache.toml", {"terrain.smooth_radius=20"});
  if (before) setenv("TALUS_CACHE_DIR", saved.c_str(), 1);
  else unsetenv("TALUS_CACHE_DIR");
  ASSERT_FALSE(a.notes.empty());
  EXPECT_NE(a.notes[0].find("built"), std::string::npos) << a.notes[0];
  EXPECT_NE(a.notes[0].find(cache), std::string::npos) << a.notes[0];
  EXPECT_NE(b.notes[0].find("reused"), std::string::npos) << b.notes[0];
  EXPECT_NE(c.notes[0].find("built"), std::string::npos) << "new inputs, new level set: " << c.notes[0];
  // Same inputs, same terrain: identical seeding.
  EXPECT_EQ(a.bodies[0].particles, b.bodies[0].particles);
  // The default domain spans the DEM; the local origin is its lower corner (x ~ 2.6e6 m).
  EXPECT_DOUBLE_EQ(a.settings.origin.x(), 2600000);
  EXPECT_DOUBLE_EQ(a.settings.origin.y(), 1200000);
}

// A run keeps the terrain's level set only around its active blocks (Sdf::focus, from the
// terrain collider's cache), unless an erodible bed is there to project its pools onto the
// ground wherever they lie (ErodibleBed::release): then the level set stays whole.
TEST(TerrainLevelSet, ARunKeepsTheTerrainAroundItsBlocksUnlessAnErodibleBedReadsItAnywhere) {
  test::useTestTerrainCache();
  const std::string scene = R"([simulation]
dx = 5
end_time = 1
[terrain]
synthetic = { kind = "slope_valley", cell_size = 10 }
boundary = "slip"
[[materials]]
name = "snow"
model = "elastic"
density = 300
youngs_modulus = 1e6
[[materials]]
name = "cover"
model = "elastic"
density = 100
youngs_modulus = 1e6
[[bodies]]
kind = "layer"
material = "snow"
thickness = 20
bounds = [2600900, 1200100, 2601200, 1200300]
)";
  const std::string cover = "\n[[bodies]]\nkind = \"layer\"\nmaterial = \"cover\"\nthickness = 1\n"
                            "erosion_energy = 200\nbounds = [2601250, 1200100, 2601380, 1200300]\n";
  // Whether the terrain still answers far from the release after a step.
  auto answersFarAway = [](const std::string& text) {
    SceneSetup s = loadSceneString(text, "focus.toml");
    const std::shared_ptr<const Sdf> terrain = s.settings.terrain;
    Vec3d lo, hi;
    terrain->bounds(lo, hi);
    Simulation sim(s.settings, std::move(s.groups));
    EXPECT_GT(sim.particleCount(), 0u);
    sim.step();
    try {
      terrain->distance(Vec3d(lo.x() + 5, hi.y() - 5, 0.5 * (lo.z() + hi.z())));
      return true;
    } catch (const std::logic_error&) {
      return false;
    }
  };
  EXPECT_FALSE(answersFarAway(scene)) << "the run kept the whole terrain";
  SceneSetup check = loadSceneString(scene + cover, "focus.toml");
  ASSERT_FALSE(check.settings.covers.empty()) << "the cover was not made an erodible field";
  EXPECT_TRUE(answersFarAway(scene + cover)) << "an erodible bed's terrain was cut to the blocks";
}
