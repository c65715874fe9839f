// AIMEC path analysis (hazard/aimec): (s, l) grids, run-out by a threshold, area classes against a
// reference, the start of the run-out area, on fields whose answers are known; and the
// `map-stats --aimec` / `compare --aimec` commands.
#include "hazard/aimec.h"
#include "terrain_test_support.h"
#include "tools/analysis.h"

#include <cmath>
#include <filesystem>
#include <gtest/gtest.h>

using namespace talus;
namespace fs = std::filesystem;

namespace {

constexpr double kW = 2600000, kS = 1200000; // south-west corner of the test rasters (EPSG:2056)

/// 1000 m x 400 m, 5 m cells: `f` at the cell centres.
DemRaster field(const std::function<double(double, double)>& f) { return test::makeDem(200, 80, 5, kW, kS, f); }

/// A tongue 2 (units) high from x = 100 to 600 m, 80 m wide around y = 200 m, 0 elsewhere.
double tongue(double x, double y, double shift = 0) {
  return x - kW >= 100 + shift && x - kW <= 600 + shift && std::abs(y - kS - 200) <= 40 ? 2.0 : 0.0;
}

const Polyline kPath({{kW + 50, kS + 200}, {kW + 950, kS + 200}}); // along the tongue, s = x - 50

} // namespace

TEST(Aimec, RunoutOfAStraightTongueIsItsFarEndWithinACell) {
  const DemRaster r = field([](double x, double y) { return tongue(x, y); });
  const aimec::Transform t = aimec::makeTransform(kPath, 600, 5);
  EXPECT_EQ(t.nl % 2, 1u); // l = 0 is a lane
  EXPECT_NEAR(t.s.back(), 900, 1e-9);
  const aimec::PathStats p = aimec::analyse(t, aimec::resample(t, r), 1.0);
  ASSERT_TRUE(p.found);
  // Bilinear between cell centres moves the 1.0 crossing of a 0 -> 2 step by at most half a
  // cell; the (s, l) grid adds one more cell: 2 cells in all.
  EXPECT_NEAR(p.sStart, 100 - 50, 10);
  EXPECT_NEAR(p.sRunout, 600 - 50, 10);
  EXPECT_NEAR(p.deltaSXY, 500, 10);
  EXPECT_NEAR(p.xRunout, kW + 600, 10);
  EXPECT_NEAR(p.mma, 2.0, 1e-6);
  EXPECT_LE(std::abs(p.lRunout), 40 + 5);
  // A threshold above the field: nothing found, nothing invented.
  EXPECT_FALSE(aimec::analyse(t, aimec::resample(t, r), 2.5).found);
}

TEST(Aimec, SectionIntegralsOfATongueAreItsWidthTimesItsHeightAndSumToItsVolume) {
  // The tongue (2 units over 500 m x 80 m): per metre of path 2 x 80 = 160 in its middle, 0
  // beyond it; summed over s, its volume 2 x 500 x 80 = 80 000 (what `map-stats --aimec --scale
  // RHO` turns into an erosion depth's kg per metre and in all).
  const DemRaster r = field([](double x, double y) { return tongue(x, y); });
  const aimec::Transform t = aimec::makeTransform(kPath, 600, 5);
  const aimec::PathStats p = aimec::analyse(t, aimec::resample(t, r), 1.0);
  ASSERT_EQ(p.crossIntegral.size(), t.ns);
  double sum = 0;
  for (size_t i = 0; i < t.ns; ++i) {
    sum += p.crossIntegral[i] * t.cellSize;
    if (std::abs(t.s[i] - 300) < 150) { EXPECT_NEAR(p.crossIntegral[i], 160, 160 * 0.07) << "s " << t.s[i]; }
    if (t.s[i] > 600) { EXPECT_EQ(p.crossIntegral[i], 0.0) << "s " << t.s[i]; }
  }
  // Bilinear sampling between cell centres smears the edges by half a cell either way, which
  // cancels in the sum; the lanes' cells tile the corridor: within 1 %.
  std::printf("  tongue volume along the path %.1f (80 000)\n", sum);
  EXPECT_NEAR(sum, 80000, 800);
}

TEST(Aimec, AreasAgainstAShiftedReferenceAreTheShiftTimesTheWidth) {
  const DemRaster ref = field([](double x, double y) { return tongue(x, y); });
  const DemRaster sim = field([](double x, double y) { return tongue(x, y, 60); });
  const aimec::Transform t = aimec::makeTransform(kPath, 600, 5);
  const aimec::AreaComparison c = aimec::compareAreas(t, aimec::resample(t, sim), aimec::resample(t, ref), 1.0);
  // 60 m x 80 m appear only in the simulation (FP), the same only in the reference (FN), and
  // 440 m x 80 m in both; edges are resolved to a cell (5 m) on each side: 2 cells of slack.
  const double w = 80, cell = 5;
  EXPECT_NEAR(c.fp, 60 * w, 2 * cell * (60 + w));
  EXPECT_NEAR(c.fn, 60 * w, 2 * cell * (60 + w));
  EXPECT_NEAR(c.tp, 440 * w, 2 * cell * (440 + w));
  EXPECT_NEAR(c.alphaTP, c.tp / (c.tp + c.fn), 1e-12); // normalised by the reference's area
  EXPECT_NEAR(c.runoutDifference, 60, 2 * cell);
  // Against itself: all true positive.
  const aimec::AreaComparison self = aimec::compareAreas(t, aimec::resample(t, ref), aimec::resample(t, ref), 1.0);
  EXPECT_EQ(self.fp, 0);
  EXPECT_EQ(self.fn, 0);
  EXPECT_DOUBLE_EQ(self.alphaTP, 1.0);
  EXPECT_DOUBLE_EQ(self.runoutDifference, 0.0);
}

TEST(Aimec, OnACurvedPathLanesFanOutAndTheAreasAddUpToTheCorridor) {
  // A quarter circle of radius R = 300 m turning left (counter-clockwise), a vertex every degree:
  // lane l runs at radius R - l, so its length is L (1 - l / R), and the cells of all lanes add up
  // to L x W (the outer and inner excess cancel). AIMEC assumes the cross-sections do not cross,
  // i.e. W / 2 < R; here W = 105 m (21 lanes of 5 m).
  std::vector<Eigen::Vector2d> arc;
  const double R = 300, cx = kW + 100, cy = kS + 400;
  for (int a = -90; a <= 0; ++a) arc.emplace_back(cx + R * std::cos(a * M_PI / 180), cy + R * std::sin(a * M_PI / 180));
  const Polyline path(arc);
  const aimec::Transform t = aimec::makeTransform(path, 100, 5);
  for (size_t i = 1; i < t.ns; ++i) EXPECT_GT(t.s[i], t.s[i - 1]);
  double all = 0, inner = 0, outer = 0;
  for (size_t i = 0; i < t.ns; ++i) {
    for (size_t k = 0; k < t.nl; ++k) all += t.area[t.index(i, k)];
    inner += t.area[t.index(i, t.nl - 1)] / t.cellSize, outer += t.area[t.index(i, 0)] / t.cellSize;
  }
  const double L = path.length(), W = double(t.nl) * t.cellSize, l = t.l.back();
  // Within 1 %: the sampled arc is a polygon, and the ends are half cells.
  EXPECT_NEAR(all, L * W, 0.01 * L * W);
  EXPECT_NEAR(inner, L * (1 - l / R), 0.01 * L);
  EXPECT_NEAR(outer, L * (1 + l / R), 0.01 * L);
}

TEST(Aimec, ElevationsGiveTheRunoutAngleAndRealAreas) {
  // A plane dropping 0.5 m per m eastwards: the thalweg angle is atan(0.5) = 26.57 deg, and a
  // cell's real area is its plan area times sqrt(1 + 0.25).
  const DemRaster dem = field([](double x, double) { return 2000 - 0.5 * (x - kW); });
  const DemRaster r = field([](double x, double y) { return tongue(x, y); });
  const aimec::Transform t = aimec::makeTransform(kPath, 100, 5, &dem);
  const aimec::PathStats p = aimec::analyse(t, aimec::resample(t, r), 1.0);
  EXPECT_NEAR(p.runoutAngle, std::atan(0.5) * 180 / M_PI, 0.01);
  EXPECT_NEAR(p.deltaZ, 0.5 * p.deltaSXY, 1e-6);
  EXPECT_NEAR(t.area[t.index(10, 5)], 25 * std::sqrt(1.25), 1e-6);
  // The run-out area starts where the thalweg flattens below the angle: never on this plane at
  // 20 deg, at once at 30 deg.
  EXPECT_EQ(aimec::runoutAreaStart(t, 20, nullptr), t.ns);
  EXPECT_EQ(aimec::runoutAreaStart(t, 30, nullptr), 0u);
}

TEST(Aimec, MapStatsAndCompareCommandsWriteTheirPictures) {
  const std::string dir = test::tempDir("aimec_commands");
  writeDemGeoTiff(field([](double x, double y) { return tongue(x, y); }), dir + "/ref.tif");
  writeDemGeoTiff(field([](double x, double y) { return tongue(x, y, 60); }), dir + "/sim.tif");
  const std::string path = "--path \"" + std::to_string(kW + 50) + "," + std::to_string(kS + 200) + " " +
                           std::to_string(kW + 950) + "," + std::to_string(kS + 200) + "\"";
  std::string out;
  ASSERT_EQ(test::runTalus("map-stats " + dir + "/sim.tif --aimec --threshold 1 " + path + " --png " + dir +
                               "/sl.png --plot " + dir + "/along.png --out " + dir + "/along.csv",
                           out),
            0)
      << out;
  EXPECT_NE(out.find("s_runout"), std::string::npos) << out;
  for (const char* f : {"/sl.png", "/along.png", "/along.csv"}) EXPECT_TRUE(fs::exists(dir + f)) << f;
  ASSERT_EQ(test::runTalus("compare " + dir + "/sim.tif " + dir + "/ref.tif --aimec --threshold 1 " + path + " --png " +
                               dir + "/areas.png",
                           out),
            0)
      << out;
  EXPECT_NE(out.find("d_runout"), std::string::npos) << out;
  EXPECT_TRUE(fs::exists(dir + "/areas.png"));
  // Without a path the analysis cannot run: one line, a non-zero exit.
  const int rc = test::runTalus("map-stats " + dir + "/sim.tif --aimec", out);
  EXPECT_NE(rc, 0);
  EXPECT_NE(out.find("--path"), std::string::npos) << out;
}

TEST(Aimec, TheReferenceAgainstItselfAlongItsOwnPath) {
  if (test::sharedDir().empty()) GTEST_SKIP() << "../shared (AvaFrame avaWog data) not found";
  const std::string base = test::sharedDir() + "/data/avaframe_avaWog/";
  const DemRaster ppr = analysis::readRaster(base + "reference_com1DFA_avaWogNullTest/relWog_005698a9de_C_L_null_dfa_ppr.asc");
  const aimec::Transform t = aimec::makeTransform(Polyline::parse(base + "Inputs/LINES/path_aimec.shp"), 600, 5);
  const std::vector<float> f = aimec::resample(t, ppr);
  const aimec::PathStats p = aimec::analyse(t, f, 1.0);
  ASSERT_TRUE(p.found);
  // `talus map-stats` finds the run-out by projecting every cell onto the path (the farthest cell
  // reaching 1 kPa within 300 m of it); AIMEC's cross-sections must find the same end within
  // three cells (15 m): they differ only in how a cell is assigned its s.
  const Polyline path = Polyline::parse(base + "Inputs/LINES/path_aimec.shp");
  const analysis::MapStats m = analysis::mapStats(ppr, std::nextafter(1.0, 2.0), nullptr, &path, 300);
  EXPECT_NEAR(p.sRunout, m.runout, 15);
  const aimec::AreaComparison c = aimec::compareAreas(t, f, f, 1.0);
  EXPECT_DOUBLE_EQ(c.alphaTP, 1.0);
}
