// Post-processing (tools/analysis): raster sampling, profiles, map statistics, comparisons with a
// reference, series summaries; and the probe that moves with the flow ([[output.probes]]).
#include "io/run/run_driver.h"
#include "terrain_test_support.h"
#include "tools/analysis.h"

#include <cmath>
#include <fstream>
#include <gtest/gtest.h>

using namespace talus;
using namespace talus::analysis;

namespace {

constexpr double kX0 = 2600000, kY0 = 1200000;

DemRaster raster(int nx, int ny, double cell, const std::function<double(double, double)>& f) {
  return test::makeDem(nx, ny, cell, kX0, kY0, f);
}

} // namespace

TEST(Analysis, BilinearSamplingIsExactOnAPlaneAndNaNOutside) {
  const DemRaster r = raster(20, 10, 2, [](double x, double y) { return 3 + 0.5 * (x - kX0) - 0.25 * (y - kY0); });
  for (double x : {1.0, 2.7, 17.3, 38.9})
    for (double y : {1.0, 5.5, 18.9})
      EXPECT_NEAR(sample(r, kX0 + x, kY0 + y), 3 + 0.5 * x - 0.25 * y, 1e-4) << x << " " << y;
  // Within half a cell of the edge the outermost centres are extended; beyond the raster, NaN.
  EXPECT_NEAR(sample(r, kX0 + 0.5, kY0 + 5), 3 + 0.5 * 1 - 0.25 * 5, 1e-4);
  EXPECT_TRUE(std::isnan(sample(r, kX0 - 0.1, kY0 + 5)));
  EXPECT_TRUE(std::isnan(sample(r, kX0 + 5, kY0 + 20.1)));
  DemRaster holed = r;
  int c, row;
  ASSERT_TRUE(holed.grid.locate(kX0 + 11, kY0 + 11, c, row));
  holed.height[holed.grid.index(c, row)] = NAN;
  EXPECT_TRUE(std::isnan(sample(holed, kX0 + 11.5, kY0 + 10.5))); // needs the hole
  EXPECT_FALSE(std::isnan(sample(holed, kX0 + 5, kY0 + 5)));
}

TEST(Analysis, PolylineParsesProjectsAndProfilesSampleAlongIt) {
  const Polyline l = Polyline::parse("2600002,1200010 2600032,1200010 2600032,1200050");
  EXPECT_DOUBLE_EQ(l.length(), 70);
  EXPECT_NEAR((l.at(45) - Eigen::Vector2d(2600032, 1200025)).norm(), 0, 1e-9);
  double off = 0;
  bool beyond = true;
  EXPECT_NEAR(l.project(Eigen::Vector2d(2600012, 1200013), &off, &beyond), 10, 1e-9);
  EXPECT_NEAR(off, 3, 1e-9); // left of the direction of travel
  EXPECT_FALSE(beyond);
  EXPECT_NEAR(l.project(Eigen::Vector2d(2600032, 1200060), &off, &beyond), 70, 1e-9);
  EXPECT_TRUE(beyond);
  EXPECT_THROW(Polyline::parse("2600000,1200010"), std::invalid_argument);
  EXPECT_THROW(Polyline::parse("2600000,1200010 abc"), std::invalid_argument);

  const DemRaster r = raster(40, 40, 2, [](double x, double y) { return (x - kX0) + 2 * (y - kY0); });
  const Profile p = profile(l, {&r}, 4);
  ASSERT_EQ(p.s.size(), 19u); // 0, 4, ..., 68, and the end at 70
  EXPECT_DOUBLE_EQ(p.s.back(), 70);
  for (size_t i = 0; i < p.s.size(); ++i)
    EXPECT_NEAR(p.values[0][i], (p.x[i] - kX0) + 2 * (p.y[i] - kY0), 1e-3) << p.s[i];
}

TEST(Analysis, PolylineFromALineShapefile) {
  GDALAllRegister();
  const std::string dir = test::tempDir("analysis_line");
  const std::string path = dir + "/line.shp";
  GDALDataset* ds = GetGDALDriverManager()->GetDriverByName("ESRI Shapefile")->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr);
  ASSERT_TRUE(ds);
  OGRLayer* layer = ds->CreateLayer("line", nullptr, wkbLineString, nullptr);
  OGRFeature* f = OGRFeature::CreateFeature(layer->GetLayerDefn());
  OGRLineString ls;
  ls.addPoint(2600000, 1200000);
  ls.addPoint(2600300, 1200400);
  f->SetGeometry(&ls);
  ASSERT_EQ(layer->CreateFeature(f), OGRERR_NONE);
  OGRFeature::DestroyFeature(f);
  GDALClose(ds);
  EXPECT_NEAR(Polyline::parse(path).length(), 500, 1e-9);
}

TEST(Analysis, MapStatsGiveAreaVolumeGroundReachedAndRunout) {
  // A 2 m thick block 20 m x 10 m (cells of 1 m) on a plane rising 0.5 m per m northwards.
  const DemRaster h = raster(60, 40, 1, [](double x, double y) {
    const double X = x - kX0, Y = y - kY0;
    return X > 10 && X < 30 && Y > 10 && Y < 20 ? 2.0 : 0.0;
  });
  const DemRaster ground = raster(60, 40, 1, [](double, double y) { return 1000 + 0.5 * (y - kY0); });
  const Polyline path({{kX0, kY0 + 15}, {kX0 + 50, kY0 + 15}});
  const MapStats m = mapStats(h, 0.1, &ground, &path, 20);
  EXPECT_EQ(m.cells, 200u);
  EXPECT_DOUBLE_EQ(m.area, 200);
  EXPECT_DOUBLE_EQ(m.volume, 400);
  EXPECT_DOUBLE_EQ(m.max, 2);
  EXPECT_DOUBLE_EQ(m.mean, 2);
  EXPECT_NEAR(m.groundMin, 1000 + 0.5 * 10.5, 1e-3);
  EXPECT_NEAR(m.groundMax, 1000 + 0.5 * 19.5, 1e-3);
  EXPECT_NEAR(m.runout, 29.5, 1e-9); // the easternmost cell centre
  EXPECT_FALSE(m.runoutBeyondEnd);
  EXPECT_EQ(mapStats(h, 2.5).cells, 0u);
  EXPECT_NEAR(mapStats(h, 0.1, nullptr, &path, 0.5).runout, 29.5, 1e-9); // cells next to the line
  const Polyline far({{kX0, kY0 + 35}, {kX0 + 50, kY0 + 35}});
  EXPECT_TRUE(std::isnan(mapStats(h, 0.1, nullptr, &far, 5).runout)); // no counted cell within 5 m
}

TEST(Analysis, ComparisonOfShiftedDiscsOnDifferentGrids) {
  // Reference: a disc of radius 50 m on 5 m cells; simulation: the same disc 10 m further east
  // on 2 m cells with another origin. Overlap of two unit discs shifted by d/r = 0.2:
  // lens area / union, with lens = 2 r^2 acos(d/2r) - (d/2) sqrt(4 r^2 - d^2).
  const double r = 50, d = 10;
  auto disc = [&](double cx) {
    return [=](double x, double y) { return std::hypot(x - cx, y - (kY0 + 100)) < r ? 3.0 : 0.0; };
  };
  const DemRaster ref = test::makeDem(40, 40, 5, kX0, kY0, disc(kX0 + 100));
  const DemRaster simRaw = test::makeDem(110, 110, 2, kX0 - 5, kY0 - 5, disc(kX0 + 100 + d));
  const DemRaster sim = resample(simRaw, ref.grid);
  const Comparison c = compare(sim, ref, 1.0, nullptr);
  const double lens = 2 * r * r * std::acos(d / (2 * r)) - 0.5 * d * std::sqrt(4 * r * r - d * d);
  const double disk = M_PI * r * r;
  EXPECT_NEAR(c.ref.area, disk, 0.05 * disk);
  EXPECT_NEAR(c.sim.area, disk, 0.05 * disk);
  EXPECT_NEAR(c.overlap, lens / (2 * disk - lens), 0.03);
  EXPECT_NEAR(c.areaSimOnly, c.areaRefOnly, 0.1 * c.areaRefOnly);
  // Identical rasters: full overlap, no bias.
  const Comparison same = compare(ref, ref, 1.0);
  EXPECT_DOUBLE_EQ(same.overlap, 1);
  EXPECT_DOUBLE_EQ(same.bias, 0);
  EXPECT_DOUBLE_EQ(same.rmse, 0);
  const auto cls = overlapClasses(sim, ref, 1.0);
  int c2 = 0, c3 = 0, c1 = 0;
  for (float v : cls) c1 += v == 1.f, c2 += v == 2.f, c3 += v == 3.f;
  EXPECT_NEAR(c2 * 25.0, c.areaBoth, 1e-6);
  EXPECT_NEAR(c3 * 25.0, c.areaSimOnly, 1e-6);
  EXPECT_NEAR(c1 * 25.0, c.areaRefOnly, 1e-6);
  // Run-out along a west-east path through the centres: the simulation's reaches 10 m farther.
  const Polyline path({{kX0, kY0 + 100}, {kX0 + 200, kY0 + 100}});
  const Comparison cp = compare(sim, ref, 1.0, &path, 10);
  EXPECT_NEAR(cp.sim.runout - cp.ref.runout, d, 5.0 + 1e-9); // one reference cell
}

TEST(Analysis, SeriesRestTimeAndFrontSpeedAgainstDistance) {
  const std::string dir = test::tempDir("analysis_series");
  {
    std::ofstream f(dir + "/series.csv");
    f << "time_s,dt_s,kinetic_energy_J_total,front_m_a\n";
    // Kinetic energy peaks at t = 2 s and decays; the front moves 20 m/s from 50 m, then stops.
    for (int i = 0; i <= 100; ++i) {
      const double t = 0.1 * i;
      const double ke = t < 2 ? 100 * t : 200 * std::exp(-(t - 2));
      const double front = t < 5 ? 50 + 20 * t : 150;
      f << t << ",0.01," << ke << "," << front << "\n";
    }
  }
  const SeriesTable t = readSeries(dir + "/series.csv");
  ASSERT_EQ(t.rows.size(), 101u);
  // 200 e^-(t-2) < 2 from t - 2 > ln 100 = 4.605: the first row after is t = 6.7.
  EXPECT_NEAR(timeBelowFraction(t, "kinetic_energy_J_total", 0.01), 6.7, 1e-9);
  EXPECT_TRUE(std::isnan(timeBelowFraction(t, "kinetic_energy_J_total", 1e-9)));
  const FrontSpeed fs = frontSpeedAgainstDistance(t, "a", 5, 10);
  ASSERT_FALSE(fs.s.empty());
  int checked = 0;
  for (size_t i = 0; i < fs.s.size(); ++i) {
    if (fs.s[i] > 50) {
      EXPECT_NEAR(fs.arrival[i], (fs.s[i] - 50) / 20, 1e-6) << fs.s[i];
    }
    if (fs.s[i] >= 65 && fs.s[i] <= 140) {
      EXPECT_NEAR(fs.speed[i], 20, 1e-6) << fs.s[i];
      ++checked;
    }
  }
  EXPECT_GT(checked, 10);
}

TEST(Analysis, ProbeMovesWithARigidlyTranslatingBlock) {
  // No gravity: an elastic block moving at (3, -1, 0.5) m/s; the probe starts at its centre
  // (given in x and y only, so it starts at the block's mean height) and must follow it. A
  // second block at rest, far enough away never to share a grid node, holds a probe that must
  // report zero speed: each probe sees only its own materials.
  const std::string dir = test::tempDir("analysis_probe");
  SceneSetup s = loadSceneString(R"([simulation]
dx = 0.5
end_time = 1.0
gravity = [0, 0, 0]
[domain]
min = [2600000, 1200000, 500]
max = [2600020, 1200020, 520]
[[materials]]
name = "block"
model = "elastic"
density = 1000
youngs_modulus = 1e6
[[materials]]
name = "still"
model = "elastic"
density = 1000
youngs_modulus = 1e6
[[bodies]]
material = "block"
shape = "box"
min = [2600004, 1200008, 504]
max = [2600008, 1200012, 506]
velocity = [3, -1, 0.5]
[[bodies]]
material = "still"
shape = "box"
min = [2600004, 1200015, 504]
max = [2600008, 1200018, 506]
[output]
series_interval = 0.25
[[output.probes]]
name = "p0"
point = [2600006, 1200010]
materials = ["block"]
[[output.probes]]
name = "still"
point = [2600006, 1200016.5, 505]
materials = ["still"]
)",
                                 "probe.toml");
  RunOptions opt;
  opt.outDir = dir;
  opt.progress = false;
  ASSERT_TRUE(runScene(std::move(s), opt).ok);
  const SeriesTable t = readSeries(dir + "/series.csv");
  const int sp = t.column("probe_speed_m_s_p0"), px = t.column("probe_x_m_p0"), py = t.column("probe_y_m_p0"),
            pz = t.column("probe_z_m_p0");
  ASSERT_GE(sp, 0);
  ASSERT_GE(pz, 0);
  const double v = std::sqrt(9 + 1 + 0.25);
  const int still = t.column("probe_speed_m_s_still");
  ASSERT_GE(still, 0);
  for (const auto& r : t.rows) {
    EXPECT_NEAR(r[size_t(still)], 0, 1e-6) << r[0];
    EXPECT_NEAR(r[size_t(sp)], v, 1e-4) << r[0];
    EXPECT_NEAR(r[size_t(px)], 2600006 + 3 * r[0], 1e-3) << r[0];
    EXPECT_NEAR(r[size_t(py)], 1200010 - 1 * r[0], 1e-3) << r[0];
    EXPECT_NEAR(r[size_t(pz)], 505 + 0.5 * r[0], 1e-3) << r[0];
  }
  EXPECT_NEAR(t.rows.back()[0], 1.0, 1e-9);

  // A probe whose point holds no particle of its materials is refused at the start.
  SceneSetup bad = loadSceneString(R"([simulation]
dx = 0.5
end_time = 0.1
gravity = [0, 0, 0]
[domain]
min = [0, 0, 0]
max = [10, 10, 10]
[[materials]]
name = "block"
model = "elastic"
density = 1000
youngs_modulus = 1e6
[[bodies]]
material = "block"
shape = "box"
min = [1, 1, 1]
max = [3, 3, 3]
[[output.probes]]
point = [8, 8, 8]
)",
                                   "probe_bad.toml");
  try {
    runScene(std::move(bad), opt);
    ADD_FAILURE() << "a probe without material at its point was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("probe 'probe0'"), std::string::npos) << e.what();
  }
}
