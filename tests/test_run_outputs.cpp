// `talus run` outputs: particles.h5 layout and summary.json contents.
#include "io/common/h5_file.h"
#include "io/run/run_driver.h"
#include "test_support.h"

#include <fstream>
#include <gtest/gtest.h>
#include <sstream>

using namespace talus;

TEST(RunOutputs, ParticlesH5AndSummaryJsonDescribeTheFinalState) {
  const std::string dir = test::tempDir("run_outputs");
  SceneSetup scene = loadSceneString(defaultSceneText(), "default.toml",
                                     {"simulation.end_time=0.05", "output.frame_interval=0.025"});
  size_t n = 0;
  for (const auto& g : scene.groups) n += g->size();
  RunOptions opt;
  opt.outDir = dir;
  opt.progress = false;
  const RunResult r = runScene(std::move(scene), opt);
  ASSERT_TRUE(r.ok) << r.error;

  h5::Handle f = h5::openFile(dir + "/particles.h5");
  size_t rows = 0, cols = 0;
  const auto pos = h5::readDataset<double>(f, "/particles/position", rows, cols);
  EXPECT_EQ(rows, n);
  EXPECT_EQ(cols, 3u);
  const auto mat = h5::readDataset<int32_t>(f, "/particles/material", rows, cols);
  EXPECT_EQ(rows, n);
  EXPECT_EQ(cols, 1u);
  h5::readDataset<float>(f, "/particles/velocity", rows, cols);
  EXPECT_EQ(cols, 3u);
  EXPECT_NEAR(h5::readDoubleAttribute(f, "time"), 0.05, 1e-12);
  EXPECT_EQ(h5::readStringsAttribute(f, "material_names"), (std::vector<std::string>{"rock", "snow"}));
  for (int frame = 0; frame < 3; ++frame) {
    char name[64];
    std::snprintf(name, sizeof name, "/frames/particles_%05d.h5", frame);
    EXPECT_TRUE(std::filesystem::exists(dir + name)) << name;
  }

  std::ifstream in(dir + "/summary.json");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string json = ss.str();
  for (const char* key : {"\"steps\"", "\"simulated_time\": 0.05", "\"wall_seconds\"", "\"threads\"",
                          "\"particles\": " , "\"particle_steps_per_second\"", "\"mass_initial\"", "\"mass_final\"",
                          "\"mass_removed\": 0", "\"max_speed\"", "\"bbox_min\"", "\"bbox_max\""})
    EXPECT_NE(json.find(key), std::string::npos) << key;
}
