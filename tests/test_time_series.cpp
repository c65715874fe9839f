// series.csv against analytic motion: kinetic energy of free fall, discharge of a uniform stream
// through sections, the front of a translating slab along a path; and the plots drawn from it.
#include "io/run/run_driver.h"
#include "test_support.h"

#include <cairo.h>
#include <cmath>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>

using namespace talus;

namespace {

struct Csv {
  std::vector<std::string> header;
  std::vector<std::vector<double>> rows;
  size_t col(const std::string& name) const {
    for (size_t i = 0; i < header.size(); ++i)
      if (header[i] == name) return i;
    ADD_FAILURE() << "no column " << name;
    return 0;
  }
};

Csv readCsv(const std::string& path) {
  Csv c;
  std::ifstream in(path);
  std::string line;
  std::getline(in, line);
  std::stringstream h(line);
  for (std::string f; std::getline(h, f, ',');) c.header.push_back(f);
  while (std::getline(in, line)) {
    std::stringstream s(line);
    std::vector<double> row;
    for (std::string f; std::getline(s, f, ',');) row.push_back(std::stod(f));
    EXPECT_EQ(row.size(), c.header.size());
    c.rows.push_back(row);
  }
  return c;
}

RunResult run(const std::string& scene, const std::string& dir) {
  SceneSetup s = loadSceneString(scene, "test.toml");
  RunOptions opt;
  opt.outDir = dir;
  opt.progress = false;
  return runScene(std::move(s), opt);
}

} // namespace

TEST(OutputSeries, KineticEnergyOfAFreeFallingBodyIsHalfMVSquared) {
  const std::string dir = test::tempDir("series_free_fall");
  const RunResult r = run(R"([simulation]
dx = 0.05
end_time = 0.3
[domain]
min = [0, 0, 0]
max = [1, 1, 2]
[[materials]]
name = "rock"
model = "elastic"
density = 2000
youngs_modulus = 1e6
[[bodies]]
material = "rock"
shape = "sphere"
center = [0.5, 0.5, 1.6]
radius = 0.2
[output]
series_interval = 0.02
)",
                          dir);
  ASSERT_TRUE(r.ok) << r.error;
  const Csv c = readCsv(dir + "/series.csv");
  ASSERT_GE(c.rows.size(), 15u); // t = 0, then every 0.02 s
  const size_t t = c.col("time_s"), ke = c.col("kinetic_energy_J_rock"), m = c.col("mass_kg_rock"),
               vmax = c.col("max_speed_m_s");
  EXPECT_EQ(c.rows[0][t], 0.0);
  EXPECT_NEAR(c.rows.back()[t], 0.3, 1e-12);
  const double mass = c.rows[0][m];
  EXPECT_NEAR(mass, 2000 * 4.0 / 3 * M_PI * 0.008, 0.05 * mass); // a lattice sphere: a few % off
  for (const auto& row : c.rows) {
    // Without contact every particle has v = g t exactly, up to float velocity storage summed
    // over ~500 steps (< 3e-5 relative), so 1e-4 relative on v^2.
    const double v = 9.81 * row[t];
    EXPECT_NEAR(row[ke], 0.5 * mass * v * v, 1e-4 * 0.5 * mass * v * v + 1e-12) << "t = " << row[t];
    EXPECT_NEAR(row[vmax], v, 1e-4 * v + 1e-12);
    EXPECT_EQ(row[m], mass);
  }
  // One row in every interval [k T, (k + 1) T): at the first step ending at or after k T (the
  // series never shortens a step, so it cannot change the run).
  for (size_t i = 1; i + 1 < c.rows.size(); ++i) EXPECT_EQ(std::floor(c.rows[i][t] / 0.02 + 1e-9), double(i));
}

namespace {
// Two 16 m slabs (materials a and b side by side, each 0.4 m x 0.4 m) moving at 10 m/s along +x
// with no gravity: a uniform stream through x = -1 for the whole 1.5 s.
const char* kStream = R"([simulation]
dx = 0.2
particles_per_cell = 27
end_time = 1.5
gravity = [0, 0, 0]
[domain]
min = [-20, -2, -2]
max = [20, 2, 2]
walls = "open"
[[materials]]
name = "a"
model = "elastic"
density = 1000
youngs_modulus = 1e4
[[materials]]
name = "b"
model = "elastic"
density = 2000
youngs_modulus = 2e4
[[bodies]]
material = "a"
shape = "box"
min = [-16.5, -0.4, 0.0]
max = [-0.5, 0.0, 0.4]
velocity = [10, 0, 0]
[[bodies]]
material = "b"
shape = "box"
min = [-16.5, 0.0, 0.0]
max = [-0.5, 0.4, 0.4]
velocity = [10, 0, 0]
[output]
series_interval = 0.5
[[output.sections]]
name = "straight"
points = [[-1, 2], [-1, -2]]
[[output.sections]]
name = "kinked"
points = [[-1, 2], [-0.7, 0.1], [-1, -2]]
[[output.sections]]
name = "reversed"
points = [[-1, -2], [-1, 2]]
[[output.sections]]
name = "lower"
points = [[-1, 2], [-1, -2]]
z_max = 0.2
[[output.paths]]
name = "axis"
points = [[-18, 0], [18, 0]]
)";
} // namespace

TEST(OutputSeries, DischargeOfAUniformStreamMatchesSpeedTimesAreaWithinTwoPercent) {
  const std::string dir = test::tempDir("series_stream");
  const RunResult r = run(kStream, dir);
  ASSERT_TRUE(r.ok) << r.error;
  const Csv c = readCsv(dir + "/series.csv");
  ASSERT_EQ(c.rows.size(), 4u); // t = 0, 0.5, 1.0, 1.5
  // Flux per material = u A = 10 m/s x 0.16 m2. A row counts whole particle layers (spacing
  // dx/3) crossing in its 0.5 s: at most one layer off out of u T / (dx/3) = 75, i.e. 1.3 %.
  const double q = 1.6;
  struct Case {
    const char* section;
    double expected;
  };
  for (const Case& k : {Case{"straight", q}, Case{"kinked", q}, Case{"reversed", -q}, Case{"lower", q / 2}}) {
    const std::string s = k.section;
    for (size_t i = 1; i < c.rows.size(); ++i) {
      const auto& row = c.rows[i];
      EXPECT_NEAR(row[c.col("discharge_m3_s_" + s + "_a")], k.expected, 0.02 * std::abs(k.expected)) << s << " " << i;
      EXPECT_NEAR(row[c.col("discharge_m3_s_" + s + "_b")], k.expected, 0.02 * std::abs(k.expected)) << s << " " << i;
      EXPECT_NEAR(row[c.col("discharge_m3_s_" + s + "_total")], 2 * k.expected, 0.02 * std::abs(2 * k.expected));
    }
    EXPECT_EQ(c.rows[0][c.col("discharge_m3_s_" + s + "_a")], 0.0);
  }
}

TEST(OutputSeries, FrontOfATranslatingSlabIsTrackedToOneCell) {
  const std::string dir = test::tempDir("series_front");
  SceneSetup s = loadSceneString(kStream, "test.toml", {"output.series_interval=0.25", "simulation.end_time=1.0"});
  RunOptions opt;
  opt.outDir = dir;
  opt.progress = false;
  ASSERT_TRUE(runScene(std::move(s), opt).ok);
  const Csv c = readCsv(dir + "/series.csv");
  ASSERT_EQ(c.rows.size(), 5u);
  const size_t t = c.col("time_s"), f = c.col("front_m_axis"), v = c.col("front_speed_m_s_axis");
  for (size_t i = 0; i < c.rows.size(); ++i) {
    // The slab's front is at x = -0.5 + 10 t, i.e. 17.5 + 10 t along the path from x = -18.
    // Bins are one cell (0.2 m): the thickness profile resolves the front to one cell.
    const double expected = 17.5 + 10 * c.rows[i][t];
    EXPECT_NEAR(c.rows[i][f], expected, 0.2) << "t = " << c.rows[i][t];
    if (i == 0) {
      EXPECT_TRUE(std::isnan(c.rows[i][v]));
    } else {
      const double dt = c.rows[i][t] - c.rows[i - 1][t];
      EXPECT_NEAR(c.rows[i][v], (c.rows[i][f] - c.rows[i - 1][f]) / dt, 1e-6);
      EXPECT_NEAR(c.rows[i][v], 10, 2 * 0.2 / dt); // two one-cell errors over the interval
    }
  }
  // The plots a user looks at first, as valid PNGs.
  for (const char* name : {"energy", "mass", "speed", "discharge", "front", "front_speed"}) {
    const std::string png = dir + "/plots/" + name + ".png";
    cairo_surface_t* img = cairo_image_surface_create_from_png(png.c_str());
    EXPECT_EQ(cairo_surface_status(img), CAIRO_STATUS_SUCCESS) << png;
    EXPECT_GT(cairo_image_surface_get_width(img), 400) << png;
    cairo_surface_destroy(img);
  }
}

/// A slab moving at 10 m/s towards a block at rest 6 m ahead, no gravity (they never meet).
const char* kSlabAndCover = R"([simulation]
dx = 0.2
particles_per_cell = 8
end_time = 0.4
gravity = [0, 0, 0]
[domain]
min = [-10, -2, -2]
max = [20, 2, 2]
walls = "open"
[[materials]]
name = "slab"
model = "elastic"
density = 1000
youngs_modulus = 1e4
[[materials]]
name = "cover"
model = "elastic"
density = 1000
youngs_modulus = 1e4
[[bodies]]
material = "slab"
shape = "box"
min = [-6, -0.4, 0]
max = [-1, 0.4, 0.4]
velocity = [10, 0, 0]
[[bodies]]
material = "cover"
shape = "box"
min = [5, -0.4, 0]
max = [12, 0.4, 0.4]
[output]
series_interval = 0.2
[[output.paths]]
name = "all"
points = [[-8, 0], [18, 0]]
[[output.paths]]
name = "moving"
points = [[-8, 0], [18, 0]]
min_speed = 1
[[output.paths]]
name = "cover_only"
points = [[-8, 0], [18, 0]]
materials = ["cover"]
)";

TEST(OutputSeries, FrontIgnoresARestingCoverWithMinSpeedAndOtherMaterials) {
  // A slab moving at 10 m/s towards a block at rest 6 m ahead (no gravity, they never meet in
  // 0.4 s). Without a speed limit the front is the resting block's far end; with min_speed it is
  // the slab's front; with materials it is that material's front.
  const std::string dir = test::tempDir("series_front_cover");
  SceneSetup s = loadSceneString(kSlabAndCover,
                                 "test.toml");
  RunOptions opt;
  opt.outDir = dir;
  opt.progress = false;
  ASSERT_TRUE(runScene(std::move(s), opt).ok);
  const Csv c = readCsv(dir + "/series.csv");
  const size_t t = c.col("time_s"), all = c.col("front_m_all"), moving = c.col("front_m_moving"),
               cover = c.col("front_m_cover_only");
  for (const auto& r : c.rows) {
    EXPECT_NEAR(r[all], 20, 0.2) << r[t];                 // x = 12, 20 m from the path's start
    EXPECT_NEAR(r[cover], 20, 0.2) << r[t];
    EXPECT_NEAR(r[moving], 7 + 10 * r[t], 0.2) << r[t];   // x = -1 + 10 t
  }
}

TEST(OutputSeries, WaterSurfaceIsTheHighestWaterParticle) {
  // A water box (model "water") beside a taller rock block, at rest without gravity for a few
  // steps. Particles sit at the centres of a lattice of spacing dx/2, so the highest water
  // particle is a quarter cell below the top of the water: 1003 - 0.025 m.
  const std::string scene = R"([simulation]
dx = 0.1
end_time = 0.01
gravity = [0, 0, 0]
[domain]
min = [0, 0, 1000]
max = [2, 1, 1005]
[[materials]]
name = "lake"
model = "water"
density = 1000
sound_speed = 20
[[materials]]
name = "rock"
model = "elastic"
density = 2500
youngs_modulus = 1e6
[[bodies]]
material = "lake"
shape = "box"
min = [0.2, 0.2, 1001]
max = [0.8, 0.8, 1003]
[[bodies]]
material = "rock"
shape = "box"
min = [1.2, 0.2, 1001]
max = [1.8, 0.8, 1004]
)";
  for (const bool listed : {false, true}) {
    const std::string dir = test::tempDir("series_water");
    SceneSetup s = loadSceneString(scene + (listed ? "[output]\nwater_materials = [\"rock\"]\n" : ""), "test.toml");
    RunOptions opt;
    opt.outDir = dir;
    opt.progress = false;
    ASSERT_TRUE(runScene(std::move(s), opt).ok);
    const Csv c = readCsv(dir + "/series.csv");
    const size_t z = c.col("max_water_surface_m");
    // Detected by model, or the materials listed (here, to check the key, the rock).
    const double top = listed ? 1004 : 1003;
    EXPECT_NEAR(c.rows[0][z], top - 0.025, 1e-4);
    EXPECT_NEAR(c.rows.back()[z], top - 0.025, 1e-3); // at rest: moved less than a millimetre
  }
  // No water, no column.
  const std::string dir = test::tempDir("series_no_water");
  std::string dry = scene;
  dry.replace(dry.find("model = \"water\""), 15, "model = \"elastic\"");
  dry.replace(dry.find("sound_speed = 20"), 16, "youngs_modulus = 1e6");
  SceneSetup s = loadSceneString(dry, "test.toml");
  RunOptions opt;
  opt.outDir = dir;
  opt.progress = false;
  ASSERT_TRUE(runScene(std::move(s), opt).ok);
  std::ifstream in(dir + "/series.csv");
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header.find("water"), std::string::npos) << header;
}

TEST(OutputSeries, EntrainedMassIsTheMassThatLeftWhereItLay) {
  // The slab (5 x 0.8 x 0.4 m, 1000 kg/m3) listed as erodible moves 10 t m: it has left
  // 0.8 x 0.4 x 10 t m3 of its place, 3200 t kg; the cover (2240 kg) at rest has left none but
  // round-off (its particles are summed in the order binning leaves them).
  const std::string dir = test::tempDir("series_entrained");
  SceneSetup s = loadSceneString(std::string(kSlabAndCover) + "[output.maps]\nerodible = [\"slab\", \"cover\"]\n", "test.toml");
  RunOptions opt;
  opt.outDir = dir;
  opt.progress = false;
  ASSERT_TRUE(runScene(std::move(s), opt).ok);
  const Csv c = readCsv(dir + "/series.csv");
  const size_t t = c.col("time_s"), slab = c.col("entrained_mass_kg_slab"), cover = c.col("entrained_mass_kg_cover");
  for (const auto& r : c.rows) {
    EXPECT_LT(r[cover], 1e-9 * 2240) << r[t];
    // The bilinear splat rounds the slab's ends over a cell (0.2 m): 0.8 x 0.4 x 0.2 x 1000 = 64 kg.
    EXPECT_NEAR(r[slab], 3200 * r[t], 64) << r[t];
  }
  EXPECT_GT(c.rows.back()[slab], 1000);
}
