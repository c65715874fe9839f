// Back-analysis (`talus calibrate`, hazard/calibration*): the loss terms against areas known by
// construction, and the recovery of a synthetic event's parameters: a Talus run at known basal
// friction and release thickness is the observation, the calibration must find both.
#include "hazard/aimec.h"
#include "hazard/calibration_loss.h"
#include "hazard/ensemble_aggregate.h"
#include "io/common/geotiff_writer.h"
#include "io/config/config_table.h"
#include "io/config/toml_reader.h"
#include "terrain_test_support.h"
#include "test_support.h"
#include "tools/analysis.h"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>

using namespace talus;
using namespace talus::calibration;
namespace fs = std::filesystem;

namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

/// A 3 m slab on the synthetic slope at basal friction 0.3, dx 10 m: a fraction of a second a run.
std::string writeScene(const std::string& dir) {
  const std::string path = dir + "/scene.toml";
  std::ofstream(path) << R"([simulation]
dx = 10.0
end_time = 20.0
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
plots = false
[ensemble]
runout_result = "pft"
runout_threshold = 0.1
path = [[2600100.0, 1200400.0], [2601300.0, 1200400.0]]
)";
  return path;
}

double number(const std::string& json, const std::string& key, size_t from = 0) {
  const auto p = json.find("\"" + key + "\": ", from);
  return p == std::string::npos ? NAN : std::stod(json.substr(p + key.size() + 4));
}

} // namespace

TEST(Calibration, FootprintTermsAreAimecsAreasOverTheObservedArea) {
  // Path along x from 0, 200 m wide domain, 10 m path-grid points at s = 0, 10, 20, ... The event
  // covers x in [105, 305]: points 110 ... 300 (20 of them per lane). The run's field is 5 kPa
  // in the map cells centred on 205 ... 385 and 0 elsewhere; resampled bilinearly between cell
  // centres it exceeds 1 kPa at s = 200 ... 390 (20 points). Both: 200 ... 300 (11); event
  // only 9, run only 9: alpha_FN = alpha_FP = 9/20 exactly (every point weighs the same here).
  const std::string dir = test::tempDir("calibration_terms");
  std::ofstream(dir + "/event.geojson")
      << R"({"type":"FeatureCollection","features":[{"type":"Feature","properties":{},"geometry":{"type":"Polygon",)"
         R"("coordinates":[[[105,-200],[305,-200],[305,200],[105,200],[105,-200]]]}}]})";
  fs::create_directories(dir + "/run/peakFiles");
  RasterGrid g;
  g.nx = 60, g.ny = 40, g.originX = 0, g.originY = 200, g.cellSize = 10;
  std::vector<float> field(g.size(), 0.0f);
  for (int r = 0; r < g.ny; ++r)
    for (int c = 0; c < g.nx; ++c) field[g.index(c, r)] = g.cellCentreX(c) > 200 && g.cellCentreX(c) < 390 ? 5.0f : 0.0f;
  writeGeoTiff(dir + "/run/peakFiles/rel_x_ppr.tif", g, field, {});
  EnsembleSettings s;
  s.path = {{0.0, 0.0}, {590.0, 0.0}};
  s.domainWidth = 180;
  ObservedEvent event({parseObservation("footprint=" + dir + "/event.geojson"), parseObservation("runout=300,10")}, s,
                      "", nullptr);
  const LossTerms t = event.evaluate(dir + "/run");
  EXPECT_NEAR(t.footprintFN, 9.0 / 20.0, 1e-9);
  EXPECT_NEAR(t.footprintFP, 9.0 / 20.0, 1e-9);
  // Run-out: the last cross-section above 1 kPa (s = 390) against the point's s = 300 m.
  EXPECT_NEAR(t.runoutObserved, 300.0, 1e-9);
  EXPECT_NEAR(t.runoutRun, 390.0, 1e-9);
  EXPECT_NEAR(t.runout, 90.0 / 300.0, 1e-12);
  EXPECT_NEAR(t.total, t.footprintFP + t.footprintFN + t.runout, 1e-12);
  EXPECT_NE(event.csvHeader().find("footprint_fp,footprint_fn,runout_run_m"), std::string::npos);
}

TEST(Calibration, ObservationsAreCheckedOneLineEach) {
  EXPECT_THROW(parseObservation("outline=x.shp"), InputError);
  EXPECT_THROW(parseObservation("runout=12"), InputError);
  EXPECT_THROW(parseObservation("footprint="), InputError);
  std::vector<Observation> o{parseObservation("runout=1,2")};
  EXPECT_THROW(applyWeight(o, "footprint=2"), InputError); // no footprint observed
  EXPECT_THROW(applyWeight(o, "runout=-1"), InputError);
  applyWeight(o, "runout=2.5");
  EXPECT_DOUBLE_EQ(o[0].weight, 2.5);
  EnsembleSettings noPath;
  EXPECT_THROW(ObservedEvent(o, noPath, "", nullptr), InputError);
}

TEST(Calibration, RecoversTheFrictionAndThicknessOfASyntheticEvent) {
  test::useTestTerrainCache();
  const std::string dir = test::tempDir("calibration_synthetic");
  const std::string scene = writeScene(dir);
  std::string out;
  ASSERT_EQ(test::runTalus("run " + scene + " --out " + dir + "/truth --quiet --set output.peak_files=true", out), 0) << out;
  const std::string truthPft = ensemble::findPeakFile(dir + "/truth", "pft");
  ASSERT_FALSE(truthPft.empty());
  // The observed run-out point: AIMEC's run-out of the true run.
  const DemRaster truth = analysis::readRaster(truthPft);
  const aimec::Transform t = aimec::makeTransform(Polyline({{2600100.0, 1200400.0}, {2601300.0, 1200400.0}}), 600,
                                                  truth.grid.cellSize);
  const aimec::PathStats ps = aimec::analyse(t, aimec::resample(t, truth), 0.1);
  ASSERT_TRUE(ps.found);
  const std::string args = "calibrate " + scene +
                           " --vary terrain.friction=0.15:0.5 --vary bodies.slab.thickness=1.5:5 --observed raster=" +
                           truthPft + " --raster-result pft --observed runout=" + std::to_string(ps.xRunout) + "," +
                           std::to_string(ps.yRunout) + " --budget 24 --jobs 2 --out " + dir + "/cal";
  ASSERT_EQ(test::runTalus(args, out), 0) << out;
  const std::string result = slurp(dir + "/cal/result.json");
  // Both parameters within 5 % of the truth (the run-out is quantised to 20 m map cells, the
  // thickness misfit to a few percent at dx 10 m), and the truth inside the plausible ranges.
  const size_t fr = result.find("terrain.friction"), th = result.find("bodies.slab.thickness");
  ASSERT_NE(fr, std::string::npos);
  ASSERT_NE(th, std::string::npos);
  EXPECT_NEAR(number(result, "value", fr), 0.3, 0.015) << result;
  EXPECT_NEAR(number(result, "value", th), 3.0, 0.15) << result;
  EXPECT_LE(number(result, "plausible_low", fr), 0.3) << result;
  EXPECT_GE(number(result, "plausible_high", fr), 0.3) << result;
  EXPECT_LE(number(result, "plausible_low", th), 3.0) << result;
  EXPECT_GE(number(result, "plausible_high", th), 3.0) << result;
  EXPECT_LT(number(result, "loss"), 0.1) << result;
  for (const char* f : {"calibration.csv", "screening.csv", "proposals.csv", "loss_terrain_friction.png",
                        "loss_bodies_slab_thickness.png", "best_against_observed.png"})
    EXPECT_TRUE(fs::exists(dir + "/cal/" + f)) << f;
  // The calibrated scene holds the best values where the author's file had them.
  auto calibrated = readTomlFile(dir + "/cal/calibrated.toml");
  EXPECT_NEAR(calibrated->table("terrain")->number("friction"), number(result, "value", fr), 1e-8);
  EXPECT_NEAR(calibrated->tables("bodies")[0]->number("thickness"), number(result, "value", th), 1e-7);
  // A second call with the same settings runs nothing new and ends where the first did.
  const std::string csv = slurp(dir + "/cal/calibration.csv");
  ASSERT_EQ(test::runTalus(args, out), 0) << out;
  EXPECT_EQ(slurp(dir + "/cal/calibration.csv"), csv);
  EXPECT_EQ(slurp(dir + "/cal/result.json"), result);
}
