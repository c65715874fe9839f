// `talus run --resume`: a run killed right after a checkpoint and resumed ends with the same
// particles, series and maps, byte for byte, as an uninterrupted run.
#include "test_support.h"

#include <cstdlib>
#include <sys/wait.h>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>

using namespace talus;

namespace {
const char* kScene = R"(
[simulation]
dx = 0.1
end_time = 0.3
[domain]
min = [0, 0, 0]
max = [3, 1, 2]
walls = "slip"
[[materials]]
name = "water"
model = "water"
density = 1000
sound_speed = 40
[[materials]]
name = "rock"
preset = "rock"
[[bodies]]
material = "water"
shape = "box"
min = [0, 0, 0]
max = [1.0, 1.0, 0.8]
[[bodies]]
material = "rock"
shape = "sphere"
center = [2.2, 0.5, 1.0]
radius = 0.25
velocity = [-6, 0, -4]
[output]
frame_interval = 0.1
checkpoint_interval = 0.08
vdb = false
maps = { cell_size = 0.2 }
[[output.sections]]
name = "gate"
points = [[1.5, 0.0], [1.5, 1.0]]
)";

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

int run(const std::string& args, const std::string& env = "") {
  const std::string cmd = env + " \"" TALUS_BINARY "\" run " + args + " --quiet --threads 2 > /dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}
} // namespace

TEST(Resume, KilledAfterACheckpointAndResumedEqualsAnUninterruptedRun) {
  const std::string dir = test::tempDir("resume");
  const std::string scene = dir + "/scene.toml";
  std::ofstream(scene) << kScene;
  ASSERT_EQ(run(scene + " --out " + dir + "/straight"), 0);
  // Dies (exit 137, like SIGKILL) right after writing its second checkpoint, at t >= 0.16 s.
  ASSERT_EQ(run(scene + " --out " + dir + "/killed", "TALUS_TEST_EXIT_AFTER_CHECKPOINT=2"), 137);
  EXPECT_FALSE(std::filesystem::exists(dir + "/killed/particles.h5"));
  ASSERT_TRUE(std::filesystem::exists(dir + "/killed/checkpoint.h5"));
  ASSERT_EQ(run(scene + " --resume " + dir + "/killed"), 0);

  for (const char* file : {"series.csv", "maps/max_flow_height_vertical.tif", "maps/max_speed.tif",
                           "frames/particles_00003.h5"}) {
    const std::string a = slurp(dir + "/straight/" + file), b = slurp(dir + "/killed/" + file);
    EXPECT_FALSE(a.empty()) << file;
    EXPECT_TRUE(a == b) << file << " differs after resume";
  }
  // The final particles: compare the datasets, not the file bytes (HDF5 headers hold no time,
  // but be robust to library layout choices).
  EXPECT_TRUE(slurp(dir + "/straight/particles.h5") == slurp(dir + "/killed/particles.h5"));
}

TEST(Resume, ResumingWithoutACheckpointIsAClearError) {
  const std::string dir = test::tempDir("resume_missing");
  const std::string scene = dir + "/scene.toml";
  std::ofstream(scene) << kScene;
  EXPECT_EQ(run(scene + " --resume " + dir + "/nowhere"), 1);
}
