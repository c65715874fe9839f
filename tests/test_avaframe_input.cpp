// AvaFrame avalanche folders as scene input (io/terrain/avaframe_folder, io/scene/avaframe_scene):
// the avaWog, avaKot and idealised folders of ../shared (skipped without it), and folders built
// here to break one rule at a time.
#include "engine/detrainment.h"
#include "engine/resistance_law.h"
#include "engine/secondary_release.h"
#include "io/scene/avaframe_scene.h"
#include "io/scene/scene.h"
#include "io/terrain/avaframe_folder.h"
#include "io/terrain/polygon_set.h"
#include "terrain_test_support.h"

#include <cmath>
#include <filesystem>
#include <functional>
#include <gtest/gtest.h>

using namespace talus;
namespace fs = std::filesystem;

namespace {

const char* kScene = R"(
[simulation]
dx = 10.0
end_time = 1.0
[terrain]
friction = 0.155
[domain]
walls = "open"
[[materials]]
name = "snow"
preset = "snow"
)";

std::string shared(const std::string& folder) { return test::sharedDir() + "/data/" + folder; }

SceneSetup load(const std::string& dir, std::vector<std::string> sets = {}) {
  test::useTestTerrainCache();
  sets.push_back(avaFrameOverride(dir));
  return loadSceneString(kScene, "test.toml", sets);
}

/// The message of the InputError `f` throws ("" when none): one line by the project's rule.
std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
    return e.what();
  }
  return "";
}

bool hasNote(const SceneSetup& s, const std::string& a, const std::string& b) {
  for (const auto& n : s.notes)
    if (n.find(a) != std::string::npos && n.find(b) != std::string::npos) return true;
  return false;
}

} // namespace

TEST(AvaFrameInput, WolfsgrubenFolderGivesItsDemReleaseEntrainmentAndPath) {
  if (test::sharedDir().empty()) GTEST_SKIP() << "../shared (AvaFrame avaWog data) not found";
  const AvaFrameFolder f = readAvaFrameFolder(shared("avaframe_avaWog"));
  EXPECT_EQ(fs::path(f.dem).filename(), "avaWog.asc");
  ASSERT_EQ(f.releases.size(), 1u);
  EXPECT_EQ(f.releases[0].name, "relWog");
  EXPECT_EQ(f.releases[0].thicknessField, "thickness");
  EXPECT_DOUBLE_EQ(f.releases[0].features.at(0).thickness, 1.0);
  ASSERT_TRUE(f.entrainment);
  EXPECT_DOUBLE_EQ(f.entrainment->features.at(0).thickness, 0.3);
  EXPECT_FALSE(f.resistance);
  // The thalweg the Wolfsgruben scene copied by hand from path_aimec.shp.
  ASSERT_EQ(f.thalweg.size(), 4u);
  EXPECT_NEAR(f.thalweg[0].x(), 169393.302490317, 1e-6);
  EXPECT_NEAR(f.thalweg[3].y(), 364371.744995566, 1e-6);
  EXPECT_TRUE(f.splitPoint);
  EXPECT_TRUE(f.demCrsWkt.empty()); // avaWog.asc has no .prj: the shapefiles' CRS is used

  const SceneSetup s = load(shared("avaframe_avaWog"));
  ASSERT_EQ(s.bodies.size(), 1u);
  EXPECT_EQ(s.bodies[0].label, "relWog");
  EXPECT_EQ(s.bodies[0].kind, "release");
  // AvaFrame's reference released 33 020 609.5 kg at 200 kg/m3: 165 103 m3, the surface area of
  // relWog times the slope-normal 1 m. Talus's quadrature of the same volume agrees within 1 %.
  EXPECT_NEAR(s.bodies[0].geometricVolume, 165103.0, 0.01 * 165103.0);
  EXPECT_EQ(crsName(s.dem->grid.crsWkt).find("Austria Lambert") != std::string::npos, true) << crsName(s.dem->grid.crsWkt);
  EXPECT_TRUE(s.output.maps.enabled);
  EXPECT_TRUE(s.output.maps.peakFiles.enabled);
  EXPECT_EQ(s.output.maps.peakFiles.releaseName, "relWog");
  EXPECT_EQ(s.output.maps.peakFiles.simType, "null");
  ASSERT_EQ(s.ensemble.path.size(), 4u); // run-outs of an ensemble are measured along it
  EXPECT_TRUE(hasNote(s, "entWog.shp", "not used"));
}

TEST(AvaFrameInput, EntrainmentAreasBecomeErodibleCoversWithTheirThickness) {
  if (test::sharedDir().empty()) GTEST_SKIP() << "../shared (AvaFrame avaWog data) not found";
  const SceneSetup a = load(shared("avaframe_avaWog"), {"avaframe.entrainment_material=snow"});
  ASSERT_EQ(a.bodies.size(), 2u);
  EXPECT_EQ(a.bodies[1].label, "entWog");
  EXPECT_EQ(a.bodies[1].kind, "layer");
  EXPECT_EQ(a.output.maps.peakFiles.simType, "ent");
  // The attribute says 0.3 m; twice the thickness, twice the volume (the release keeps its space
  // in both, so the cover's volume scales exactly up to the quadrature: 1 %).
  const SceneSetup b = load(shared("avaframe_avaWog"),
                            {"avaframe.entrainment_material=snow", "avaframe.entrainment_thickness=0.6"});
  ASSERT_GT(a.bodies[1].geometricVolume, 0);
  EXPECT_NEAR(b.bodies[1].geometricVolume / a.bodies[1].geometricVolume, 2.0, 0.02);
  // release_thickness replaces the attribute (AvaFrame's relTh): 2 m, twice the volume.
  const SceneSetup c = load(shared("avaframe_avaWog"), {"avaframe.release_thickness=2"});
  EXPECT_NEAR(c.bodies[0].geometricVolume / 165103.0, 2.0, 0.02);
}

TEST(AvaFrameInput, ResistanceAreasAreAppliedAsAvaFramesResSimulationWhenAsked) {
  if (test::sharedDir().empty()) GTEST_SKIP() << "../shared (AvaFrame avaKot data) not found";
  const AvaFrameFolder f = readAvaFrameFolder(shared("avaframe_avaKot"));
  ASSERT_TRUE(f.resistance);
  const auto regions = resistanceRegions(f);
  ASSERT_EQ(regions.size(), 2u);
  EXPECT_EQ(regions[1].feature, 1);
  EXPECT_DOUBLE_EQ(regions[0].cResH, 0.01); // AvaFrame's default (com1DFACfg.ini at the snapshot)
  // AvaFrame's null simulation by default: read, not used, and said so.
  const SceneSetup s = load(shared("avaframe_avaKot"));
  EXPECT_TRUE(hasNote(s, "resistance.shp", "not used"));
  EXPECT_EQ(s.output.maps.peakFiles.simType, "null");
  EXPECT_EQ(dynamic_cast<const ResistedLaw*>(s.settings.terrainLaw.get()), nullptr);
  // resistance = true: AvaFrame's res, the areas a drag region of the terrain law (cResH 0.01
  // inside them, 0 outside: checked where the region field is read).
  const SceneSetup r = load(shared("avaframe_avaKot"), {"avaframe.resistance=true"});
  EXPECT_TRUE(hasNote(r, "resistance.shp", "applied, drag cResH 0.0100 1/m, detrainment detK 5.0000 Pa"));
  EXPECT_EQ(r.output.maps.peakFiles.simType, "res");
  ASSERT_NE(dynamic_cast<const ResistedLaw*>(r.settings.terrainLaw.get()), nullptr);
  const auto names = r.settings.terrainLaw->parameterNames();
  EXPECT_EQ(names[names.size() - 2], "resistance");
  EXPECT_EQ(names.back(), "detrainment");
  EXPECT_NE(r.settings.terrainParameters, nullptr);
  // AvaFrame's detrainment = True by default: the detrainment phase is built; `false` drops it.
  auto detrains = [](const SceneSetup& x) {
    for (const auto& src : x.settings.sources)
      if (dynamic_cast<const Detrainment*>(src.get())) return true;
    return false;
  };
  EXPECT_TRUE(detrains(r));
  const SceneSetup d = load(shared("avaframe_avaKot"), {"avaframe.resistance=true", "avaframe.detrainment=false"});
  EXPECT_FALSE(detrains(d));
  EXPECT_TRUE(hasNote(d, "resistance.shp", "no detrainment"));
  EXPECT_NE(errorOf([&] { load(shared("avaframe_avaWog"), {"avaframe.resistance=true"}); }).find("Inputs/RES: no resistance"),
            std::string::npos);
  EXPECT_NE(errorOf([&] { load(shared("avaframe_avaKot"), {"avaframe.resistance_coefficient=0.02"}); })
                .find("needs resistance = true"),
            std::string::npos);
}

TEST(AvaFrameInput, TheDamLineBecomesADamStructureWhenAsked) {
  if (test::sharedDir().empty()) GTEST_SKIP() << "../shared (AvaFrame avaKot data) not found";
  EXPECT_TRUE(hasNote(load(shared("avaframe_avaKot")), "dam.shp", "not used"));
  const SceneSetup s = load(shared("avaframe_avaKot"), {"avaframe.dams=true"});
  ASSERT_EQ(s.settings.structures.size(), 1u);
  EXPECT_EQ(s.settings.structures[0].name, "dam");
  // avaKot's DAM/dam.shp: its second vertex (178397.855, 377753.004) has the crest at 1140 m
  // (z), 9.4 m above the DEM there; flanks at the file's slope, 60 degrees; crest dx (10 m) wide.
  const Sdf& dam = *s.settings.structures[0].geometry;
  const Vec3d o = s.settings.origin;
  EXPECT_NEAR(dam.distance(Vec3d(178397.855463071, 377753.003561389, 1141) - o), 1.0, 1e-6) << "1 m above the crest";
  EXPECT_NEAR(dam.distance(Vec3d(178397.855463071, 377753.003561389, 1138) - o), -2.0, 1e-6) << "inside, 2 m below";
  // 10 m across the line (it runs north there): 5 m beyond the crest's edge, on the 60-degree
  // flank 5 tan 60 = 8.66 m below the crest; 1131.34 m is on the flank, above it is outside.
  EXPECT_NEAR(dam.distance(Vec3d(178407.855463071, 377753.003561389, 1140 - 5 * std::tan(M_PI / 3)) - o), 0.0, 1e-6);
  EXPECT_GT(dam.distance(Vec3d(178407.855463071, 377753.003561389, 1139) - o), 0.0);
  EXPECT_NE(errorOf([&] { load(shared("avaframe_avaWog"), {"avaframe.dams=true"}); }).find("Inputs/DAM: no dam"),
            std::string::npos);
}

TEST(AvaFrameInput, IdealisedFoldersLoadWithAThicknessFromTheScene) {
  if (test::sharedDir().empty()) GTEST_SKIP() << "../shared (AvaFrame idealised data) not found";
  // Their releases carry no thickness (AvaFrame's configuration gives relTh): so must the scene.
  const std::string dam = shared("avaframe_idealized/avaDamBreak");
  const std::string e = errorOf([&] { load(dam); });
  EXPECT_NE(e.find("rel1.shp"), std::string::npos) << e;
  EXPECT_NE(e.find("release_thickness"), std::string::npos) << e;
  // A 1 m slope-normal release on the 22 degree plane holds area / cos(22 deg) x 1 m (1 %).
  const SceneSetup s = load(dam, {"avaframe.release_thickness=1"});
  const double area = PolygonSet::read(dam + "/Inputs/REL/rel1.shp").area();
  EXPECT_NEAR(s.bodies[0].geometricVolume, area / std::cos(22 * M_PI / 180), 0.01 * area);
  // The flat-plane test, FPSOL's H0 = 4 m: area x 4 m.
  const std::string fp = shared("avaframe_idealized/avaFPtest");
  const SceneSetup p = load(fp, {"avaframe.release_thickness=4"});
  const double areaFp = PolygonSet::read(fp + "/Inputs/REL/relFPCircle.shp").area();
  EXPECT_NEAR(p.bodies[0].geometricVolume, 4 * areaFp, 0.01 * 4 * areaFp);
  // avaSimilaritySol's REL/ holds rel1.prj and rel1.cpg but no rel1.shp: named, not skipped.
  const std::string sim = errorOf([&] { load(shared("avaframe_idealized/avaSimilaritySol")); });
  EXPECT_NE(sim.find("rel1"), std::string::npos) << sim;
  EXPECT_NE(sim.find("no rel1.shp"), std::string::npos) << sim;
  // The Fluchthorn folder has no release areas at all.
  const std::string flu = errorOf([&] { load(shared("avaframe_scarpFluchthorn")); });
  EXPECT_NE(flu.find("no REL/"), std::string::npos) << flu;
}

namespace {

/// A minimal AvaFrame folder: a 45 m x 45 m inclined DEM (EPSG:2056) and one release polygon.
std::string makeFolder(const std::string& name) {
  const std::string dir = test::tempDir("avaframe_" + name);
  fs::create_directories(dir + "/Inputs/REL");
  writeDemGeoTiff(test::makeDem(40, 40, 5, 2600000, 1200000, [](double x, double) { return 2000 - 0.5 * (x - 2600000); }),
                  dir + "/Inputs/dem.tif");
  test::writePolygons(dir + "/Inputs/REL/relA.shp", {{test::rectangleRing(2600020, 1200020, 2600060, 1200060), 1.5}},
                      "EPSG:2056");
  return dir;
}

} // namespace

TEST(AvaFrameInput, EachBrokenRuleIsOneLineNamingTheFile) {
  // The folder itself loads: a release of 1.5 m from the attribute.
  const std::string ok = makeFolder("ok");
  const SceneSetup s = load(ok);
  ASSERT_EQ(s.bodies.size(), 1u);
  EXPECT_EQ(s.bodies[0].label, "relA");

  EXPECT_NE(errorOf([&] { load(ok + "/nowhere"); }).find("not found"), std::string::npos);
  const std::string noInputs = test::tempDir("avaframe_noinputs");
  EXPECT_NE(errorOf([&] { load(noInputs); }).find("no Inputs/"), std::string::npos);

  const std::string two = makeFolder("twodems");
  fs::copy_file(two + "/Inputs/dem.tif", two + "/Inputs/dem2.tif");
  const std::string e2 = errorOf([&] { load(two); });
  EXPECT_NE(e2.find("more than one DEM"), std::string::npos) << e2;

  const std::string partial = makeFolder("partialthickness");
  test::writePolygons(partial + "/Inputs/REL/relB.shp",
                      {{test::rectangleRing(2600020, 1200020, 2600040, 1200040), 1.0},
                       {test::rectangleRing(2600050, 1200050, 2600070, 1200070), NAN}},
                      "EPSG:2056");
  const std::string e3 = errorOf([&] { load(partial); });
  EXPECT_NE(e3.find("relB.shp"), std::string::npos) << e3;
  EXPECT_NE(e3.find("not all features have a thickness"), std::string::npos) << e3;

  const std::string crs = makeFolder("crs");
  fs::create_directories(crs + "/Inputs/ENT");
  test::writePolygons(crs + "/Inputs/ENT/entA.shp", {{test::rectangleRing(7.0, 46.0, 7.1, 46.1), 0.3}}, "EPSG:4326");
  const std::string e4 = errorOf([&] { load(crs); });
  EXPECT_NE(e4.find("entA.shp"), std::string::npos) << e4;
  EXPECT_NE(e4.find("differs"), std::string::npos) << e4;

  const std::string scenarios = makeFolder("scenarios");
  test::writePolygons(scenarios + "/Inputs/REL/relC.shp", {{test::rectangleRing(2600020, 1200020, 2600040, 1200040), 1.0}},
                      "EPSG:2056");
  const std::string e5 = errorOf([&] { load(scenarios); });
  EXPECT_NE(e5.find("release_scenario"), std::string::npos) << e5;
  EXPECT_EQ(load(scenarios, {"avaframe.release_scenario=relC"}).bodies.at(0).label, "relC");

  const std::string negative = makeFolder("negative");
  test::writePolygons(negative + "/Inputs/REL/relA.shp", {{test::rectangleRing(2600020, 1200020, 2600060, 1200060), -1.0}},
                      "EPSG:2056");
  EXPECT_NE(errorOf([&] { load(negative); }).find("non-negative"), std::string::npos);

  // The scene brings its own DEM as well: which one would it be?
  const std::string e6 = errorOf([&] { load(ok, {"terrain.dem=\"x.tif\""}); });
  EXPECT_NE(e6.find("brings the DEM"), std::string::npos) << e6;
}

TEST(AvaFrameInput, SecondaryReleaseAreasAreHeldUntilTheFlowReachesThem) {
  const std::string dir = makeFolder("secrel");
  fs::create_directories(dir + "/Inputs/SECREL");
  test::writePolygons(dir + "/Inputs/SECREL/secB.shp", {{test::rectangleRing(2600100, 1200020, 2600140, 1200060), 1.0}},
                      "EPSG:2056");
  EXPECT_TRUE(hasNote(load(dir), "secB.shp", "not used"));
  const SceneSetup s = load(dir, {"avaframe.secondary_release=true"});
  ASSERT_EQ(s.settings.sources.size(), 1u);
  const auto* held = dynamic_cast<const SecondaryReleases*>(s.settings.sources[0].get());
  ASSERT_NE(held, nullptr);
  ASSERT_EQ(held->bodies().size(), 1u);
  EXPECT_EQ(held->bodies()[0].name, "secB");
  // 5 cm of the release material's weight per area (AvaFrame releases at the first particle).
  EXPECT_NEAR(held->bodies()[0].triggerMassPerArea, 0.05 * s.groups[0]->density(), 1e-9);
  EXPECT_FALSE(held->bodies()[0].x.empty());
  EXPECT_NE(errorOf([&] { load(makeFolder("nosecrel"), {"avaframe.secondary_release=true"}); }).find("SECREL"),
            std::string::npos);
}
