// DEM input: reading, refusing bad rasters with one clear line, no-data filling, smoothing.
#include "terrain_test_support.h"

#include <cmath>
#include <fstream>
#include <gtest/gtest.h>

using namespace talus;

namespace {

/// Expects readDem to throw a one-line InputError naming `path` and containing `part`.
void expectDemError(const std::string& path, const std::string& part, const DemReadOptions& opt = {}) {
  try {
    readDem(path, opt);
    FAIL() << "no error for " << path;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_NE(msg.find(path), std::string::npos) << msg;
    EXPECT_NE(msg.find(part), std::string::npos) << msg;
    EXPECT_EQ(msg.find('\n'), std::string::npos) << "one line: " << msg;
  }
}

double plane(double x, double y) { return 1500 + 0.5 * (x - 2600000) - 0.25 * (y - 1200000); }

} // namespace

TEST(TerrainDem, GeoTiffRoundTripKeepsGridHeightsAndCrs) {
  const std::string dir = test::tempDir("dem_roundtrip");
  const DemRaster a = test::makeDem(40, 30, 2.5, 2600000, 1200000, plane);
  writeDemGeoTiff(a, dir + "/a.tif");
  const DemRaster b = readDem(dir + "/a.tif");
  EXPECT_EQ(b.grid.nx, 40);
  EXPECT_EQ(b.grid.ny, 30);
  EXPECT_DOUBLE_EQ(b.grid.cellSize, 2.5);
  EXPECT_DOUBLE_EQ(b.grid.originX, 2600000);
  EXPECT_DOUBLE_EQ(b.grid.originY, 1200000 + 30 * 2.5);
  EXPECT_TRUE(sameCrs(a.grid.crsWkt, b.grid.crsWkt));
  EXPECT_NE(crsName(b.grid.crsWkt).find("2056"), std::string::npos) << crsName(b.grid.crsWkt);
  ASSERT_EQ(a.height.size(), b.height.size());
  for (size_t i = 0; i < a.height.size(); ++i) ASSERT_EQ(a.height[i], b.height[i]) << i; // float32 both ways
}

TEST(TerrainDem, MissingUnreadableRotatedAndNonSquareRastersAreRefused) {
  const std::string dir = test::tempDir("dem_bad");
  expectDemError(dir + "/nowhere.tif", "file not found");
  {
    std::ofstream(dir + "/text.tif") << "not a raster\n";
  }
  expectDemError(dir + "/text.tif", "not a raster");
  const std::vector<float> v(20 * 10, 1000.f);
  const double nonSquare[6] = {2600000, 5, 0, 1200100, 0, -4};
  test::writeRawRaster(dir + "/nonsquare.tif", 20, 10, nonSquare, v);
  expectDemError(dir + "/nonsquare.tif", "not square");
  const double rotated[6] = {2600000, 5, 0.5, 1200100, 0.5, -5};
  test::writeRawRaster(dir + "/rotated.tif", 20, 10, rotated, v);
  expectDemError(dir + "/rotated.tif", "rotated");
}

TEST(TerrainDem, NodataHolesAreRefusedOrFilledOnRequest) {
  const std::string dir = test::tempDir("dem_holes");
  DemRaster d = test::makeDem(30, 20, 1, 2600000, 1200000, plane);
  const size_t hole = d.grid.index(12, 9);
  d.height[hole] = NAN;
  writeDemGeoTiff(d, dir + "/hole.tif");
  expectDemError(dir + "/hole.tif", "1 no-data cells (first at column 12, row 9");
  DemReadOptions fill;
  fill.fillNodata = true;
  size_t filled = 0;
  const DemRaster f = readDem(dir + "/hole.tif", fill, &filled);
  EXPECT_EQ(filled, 1u);
  EXPECT_EQ(countNodata(f), 0u);
  // A single hole in a plane is surrounded symmetrically, so inverse-distance weighting
  // restores the plane; 0.05 m is a tenth of the 0.5 m step between neighbouring cells.
  EXPECT_NEAR(f.height[hole], plane(f.grid.cellCentreX(12), f.grid.cellCentreY(9)), 0.05);
}

TEST(TerrainDem, AssignedCrsFillsAMissingOneAndMustMatchAnExistingOne) {
  const std::string dir = test::tempDir("dem_crs");
  writeDemGeoTiff(test::makeDem(10, 10, 1, 0, 0, plane, ""), dir + "/nocrs.tif");
  writeDemGeoTiff(test::makeDem(10, 10, 1, 0, 0, plane, "EPSG:2056"), dir + "/lv95.tif");
  DemReadOptions opt;
  opt.assignCrs = "EPSG:31287";
  EXPECT_NE(crsName(readDem(dir + "/nocrs.tif", opt).grid.crsWkt).find("31287"), std::string::npos);
  expectDemError(dir + "/lv95.tif", "differs from the CRS given", opt);
}

TEST(TerrainDem, AvaWogNodataBorderIsRefusedThenFilled) {
  if (test::sharedDir().empty()) GTEST_SKIP() << "../shared (AvaFrame test data) not present";
  const std::string path = test::sharedDir() + "/data/avaframe_avaWog/Inputs/avaWog.asc";
  expectDemError(path, "94079 no-data cells");
  DemReadOptions opt;
  opt.fillNodata = true;
  size_t filled = 0;
  const DemRaster d = readDem(path, opt, &filled);
  EXPECT_EQ(filled, 94079u);
  EXPECT_EQ(countNodata(d), 0u);
  EXPECT_EQ(d.grid.nx, 490);
  EXPECT_EQ(d.grid.ny, 555);
  // The ASCII grid gives the lower-left cell centre; our origin is the north-west corner.
  EXPECT_NEAR(d.grid.cellCentreX(0), 167455.348391387, 1e-6);
  EXPECT_NEAR(d.grid.cellCentreY(d.grid.ny - 1), 361955.626633194, 1e-6);
  // Filled heights stay within the range of the data around them.
  float lo = INFINITY, hi = -INFINITY;
  for (float h : d.height) lo = std::min(lo, h), hi = std::max(hi, h);
  EXPECT_GE(lo, 1248.5f);
  EXPECT_LE(hi, 2543.8f);
}

TEST(TerrainDem, SmoothingKeepsPlanesAndDampsABumpAsTheAnalyticConvolution) {
  // Gaussian bump of width s convolved with a Gaussian of sigma = R/2 is a Gaussian of variance
  // s^2 + sigma^2 whose peak is A s^2 / (s^2 + sigma^2) (2D).
  const double A = 20, s = 8, R = 10, sigma = R / 2;
  const double xc = 2600100.5, yc = 1200100.5;
  DemRaster d = test::makeDem(201, 201, 1, 2600000, 1200000, [&](double x, double y) {
    return plane(x, y) + A * std::exp(-((x - xc) * (x - xc) + (y - yc) * (y - yc)) / (2 * s * s));
  });
  smoothDem(d, R);
  const int c = 100, r = 100; // the bump's centre cell
  const double peak = d.height[d.grid.index(c, r)] - plane(d.grid.cellCentreX(c), d.grid.cellCentreY(r));
  // 1 % of A: the kernel is truncated at 3 sigma (0.3 % of its weight) and sampled at 1 m.
  EXPECT_NEAR(peak, A * s * s / (s * s + sigma * sigma), 0.01 * A);
  // A plane is unchanged away from the edges (symmetric kernel); float heights ~1500 m carry
  // ~1e-4 m rounding, hence 2e-3 m.
  DemRaster p = test::makeDem(80, 80, 1, 2600000, 1200000, plane);
  const DemRaster before = p;
  smoothDem(p, R);
  for (int rr = 16; rr < 64; ++rr)
    for (int cc = 16; cc < 64; ++cc) ASSERT_NEAR(p.height[p.grid.index(cc, rr)], before.height[p.grid.index(cc, rr)], 2e-3);
}

TEST(TerrainDem, SmoothingSkipsNodataCells) {
  DemRaster p = test::makeDem(60, 60, 1, 2600000, 1200000, plane);
  for (int r = 20; r < 40; ++r)
    for (int c = 0; c < 10; ++c) p.height[p.grid.index(c, r)] = NAN;
  smoothDem(p, 6);
  for (int r = 20; r < 40; ++r)
    for (int c = 0; c < 10; ++c) ASSERT_TRUE(std::isnan(p.height[p.grid.index(c, r)]));
  // The cells next to the gap are averages of real heights only: finite and between the
  // plane's extremes over the kernel's reach (9 m * 0.5 m/m from the cell).
  for (int r = 20; r < 40; ++r) {
    const float h = p.height[p.grid.index(10, r)];
    ASSERT_TRUE(std::isfinite(h));
    EXPECT_NEAR(h, plane(p.grid.cellCentreX(10), p.grid.cellCentreY(r)), 4.5);
  }
}

TEST(TerrainDem, HolesOutOfTheFillRadiusAreRefusedQuicklyAndLeaveNoWorkFiles) {
  // A long thin DEM with data only at one end: the far holes are beyond the search radius.
  // (A fuzzer input of this shape took minutes and left GeoTIFF work files in the current folder.)
  const std::string dir = test::tempDir("dem_far_holes");
  const int ny = kMaxFillCells + 200;
  DemRaster d = test::makeDem(3, ny, 1, 2600000, 1200000, plane);
  for (int r = 0; r < ny - 5; ++r)
    for (int c = 0; c < 3; ++c) d.height[d.grid.index(c, r)] = NAN;
  writeDemGeoTiff(d, dir + "/far.tif");
  const auto cwd = std::filesystem::current_path();
  std::filesystem::current_path(dir);
  DemReadOptions fill;
  fill.fillNodata = true;
  expectDemError(dir + "/far.tif", "cannot be filled; crop the DEM", fill);
  std::filesystem::current_path(cwd);
  for (const auto& e : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(e.path().filename(), "far.tif") << "left behind: " << e.path();
}
