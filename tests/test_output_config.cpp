// [output] keys: defaults, every key read, bad values named by file, line and key; and only the
// outputs a scene asks for are constructed (a scene without maps builds no map accumulator).
#include "io/output/output_set.h"
#include "test_support.h"

#include <algorithm>
#include <cstring>
#include <gtest/gtest.h>

using namespace talus;

namespace {
const char* kScene = R"([simulation]
dx = 0.1
end_time = 0.1
[domain]
min = [0, 0, 0]
max = [2, 2, 2]
[[materials]]
name = "rock"
model = "elastic"
density = 2700
youngs_modulus = 1e7
[[materials]]
name = "snow cover"
model = "elastic"
density = 300
youngs_modulus = 1e6
[[bodies]]
material = "rock"
shape = "box"
min = [0.5, 0.5, 0.5]
max = [1.0, 1.0, 1.0]
)";

void expectError(const std::string& output, int line, const std::string& key, const std::string& part) {
  try {
    loadSceneString(std::string(kScene) + output, "test.toml");
    FAIL() << "no error for " << key;
  } catch (const InputError& e) {
    const std::string msg = e.what();
    EXPECT_EQ(e.line(), line) << msg;
    EXPECT_EQ(e.key(), key) << msg;
    EXPECT_NE(msg.find(part), std::string::npos) << msg;
  }
}
const int kFirst = int(std::count(kScene, kScene + std::strlen(kScene), '\n')) + 1; // first line after kScene
} // namespace

TEST(OutputConfig, DefaultsWriteHdf5AndVdbFramesAndTheSeriesOnly) {
  const SceneSetup s = loadSceneString(kScene, "test.toml");
  EXPECT_TRUE(s.output.h5Frames);
  EXPECT_TRUE(s.output.vdb);
  EXPECT_FALSE(s.output.ply);
  EXPECT_FALSE(s.output.vdbPoints);
  EXPECT_TRUE(s.output.series);
  EXPECT_FALSE(s.output.maps.enabled);
  EXPECT_TRUE(s.output.sections.empty());
}

TEST(OutputConfig, EveryKeyIsRead) {
  const SceneSetup s = loadSceneString(std::string(kScene) + R"([output]
directory = "out"
frame_interval = 0.05
crs = "EPSG:2056"
h5 = false
vdb = false
vdb_points = true
ply = true
series_interval = 0.01
plots = false
water_materials = ["snow cover"]
[output.maps]
cell_size = 0.5
per_material = true
quicklook = false
min_height = 0.05
interval = 0.02
erodible = ["snow cover"]
[[output.sections]]
name = "dam"
points = [[0.2, 1.8], [0.2, 0.2], [0.4, 0.1]]
z_min = 0.1
z_max = 1.5
[[output.paths]]
name = "thalweg"
points = [[0.1, 1.0], [1.9, 1.0]]
threshold = 0.02
half_width = 0.3
)",
                                     "test.toml");
  const OutputSettings& o = s.output;
  EXPECT_EQ(o.directory, "out");
  EXPECT_DOUBLE_EQ(o.frameInterval, 0.05);
  EXPECT_NE(o.crsWkt.find("2056"), std::string::npos);
  EXPECT_FALSE(o.h5Frames);
  EXPECT_FALSE(o.vdb);
  EXPECT_TRUE(o.vdbPoints);
  EXPECT_TRUE(o.ply);
  EXPECT_DOUBLE_EQ(o.seriesInterval, 0.01);
  EXPECT_FALSE(o.plots);
  EXPECT_EQ(o.waterMaterials, std::vector<std::string>{"snow cover"});
  EXPECT_TRUE(o.maps.enabled);
  EXPECT_DOUBLE_EQ(o.maps.cellSize, 0.5);
  EXPECT_TRUE(o.maps.perMaterial);
  EXPECT_FALSE(o.maps.quicklook);
  EXPECT_DOUBLE_EQ(o.maps.minHeight, 0.05);
  EXPECT_DOUBLE_EQ(o.maps.interval, 0.02);
  EXPECT_EQ(o.maps.erodible, std::vector<std::string>{"snow cover"});
  ASSERT_EQ(o.sections.size(), 1u);
  EXPECT_EQ(o.sections[0].name, "dam");
  ASSERT_EQ(o.sections[0].points.size(), 3u);
  EXPECT_EQ(o.sections[0].points[2], Eigen::Vector2d(0.4, 0.1));
  EXPECT_DOUBLE_EQ(o.sections[0].zMin, 0.1);
  EXPECT_DOUBLE_EQ(o.sections[0].zMax, 1.5);
  ASSERT_EQ(o.paths.size(), 1u);
  EXPECT_EQ(o.paths[0].name, "thalweg");
  EXPECT_DOUBLE_EQ(o.paths[0].threshold, 0.02);
  EXPECT_DOUBLE_EQ(o.paths[0].halfWidth, 0.3);
}

TEST(OutputConfig, MapsAsABooleanAndOverridesWork) {
  const SceneSetup s = loadSceneString(std::string(kScene) + "[output]\nmaps = true\n", "test.toml",
                                       {"output.ply=true"});
  EXPECT_TRUE(s.output.maps.enabled);
  EXPECT_TRUE(s.output.maps.perMaterial == false);
  EXPECT_TRUE(s.output.ply);
}

TEST(OutputConfig, BadValuesNameFileLineAndKey) {
  expectError("[output]\nvdb = 1\n", kFirst + 1, "output.vdb", "expected true or false");
  expectError("[output]\nmpas = true\n", kFirst + 1, "output.mpas", "did you mean 'maps'");
  expectError("[output]\ncrs = \"EPSG:99999999\"\n", kFirst + 1, "output.crs", "CRS");
  expectError("[output.maps]\nerodible = [\"ice\"]\n", kFirst + 1, "output.maps.erodible", "no material named 'ice'");
  expectError("[output.maps]\ncell_size = -1\n", kFirst + 1, "output.maps.cell_size", "positive");
  expectError("[[output.sections]]\nname = \"a\"\npoints = [[0, 0]]\n", kFirst + 2, "output.sections[0].points",
              "at least two points");
  expectError("[[output.sections]]\npoints = [[0, 0], [1, 2, 3]]\n", kFirst + 1, "output.sections[0].points",
              "[x, y] points");
  expectError("[[output.sections]]\npoints = [[0, 0], [1, 0]]\nz_min = 2\nz_max = 1\n", kFirst + 3,
              "output.sections[0].z_max", "must exceed z_min");
  expectError("[[output.paths]]\nname = \"a b\"\npoints = [[0, 0], [1, 0]]\n", kFirst + 1, "output.paths[0].name",
              "letters, digits");
  expectError("[[output.paths]]\nname = \"p\"\npoints = [[0, 0], [1, 0]]\n[[output.paths]]\nname = \"p\"\n"
              "points = [[0, 0], [1, 0]]\n",
              kFirst + 4, "output.paths[1].name", "duplicate");
  expectError("[[output.gauges]]\npoint = [1, 2, 3]\n", kFirst + 1, "output.gauges[0].point", "expected [x, y]");
  expectError("[[output.gauges]]\npoint = [1, 2]\nradius = 0\n", kFirst + 2, "output.gauges[0].radius", "positive");
  expectError("[output]\nseries = false\n[[output.gauges]]\npoint = [1, 1]\n", kFirst + 1, "output.series",
              "need series = true");
  expectError("[output]\nseries = false\n[[output.sections]]\npoints = [[0, 0], [1, 0]]\n", kFirst + 1,
              "output.series", "need series = true");
  expectError("[output]\nanimation = true\n", kFirst + 1, "output.animation", "it needs maps = true");
  expectError("[output]\nmaps = true\nanimation = { quantity = \"volume\" }\n", kFirst + 2,
              "output.animation.quantity", "thickness");
  expectError("[output]\nmaps = true\nanimation = { fps = 0 }\n", kFirst + 2, "output.animation.fps", "1");
}

TEST(OutputSet, OnlyRequestedOutputsAreConstructed) {
  const std::string dir = test::tempDir("output_set");
  auto names = [&](const std::vector<std::string>& sets) {
    const SceneSetup s = loadSceneString(kScene, "test.toml", sets);
    return OutputSet(s.output, s.runContext(), dir).names();
  };
  using V = std::vector<std::string>;
  // No frame interval: no frame writers; no maps requested: no map accumulator.
  EXPECT_EQ(names({}), V{"time_series"});
  EXPECT_EQ(names({"output.series=false"}), V{});
  EXPECT_EQ(names({"output.frame_interval=0.05"}), (V{"h5_frames", "vdb_frames", "time_series"}));
  EXPECT_EQ(names({"output.frame_interval=0.05", "output.h5=false", "output.vdb=false", "output.ply=true",
                   "output.vdb_points=true", "output.series=false", "output.maps=true"}),
            (V{"vdb_points", "ply_frames", "hazard_maps"}));
  // The run-up map comes with the maps where there is water (a material of model water).
  const std::string lake = "[[materials]]\nname = \"lake\"\nmodel = \"water\"\ndensity = 1000\nsound_speed = 20\n";
  const SceneSetup wet = loadSceneString(std::string(kScene) + lake, "test.toml", {"output.maps=true", "output.series=false"});
  EXPECT_EQ(OutputSet(wet.output, wet.runContext(), dir).names(), (V{"hazard_maps", "water_surface_map"}));
}
