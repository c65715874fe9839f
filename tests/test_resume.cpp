// `talus run --resume`: a run killed right after a checkpoint and resumed ends with the same
// particles, series and maps, byte for byte, as an uninterrupted run.
#include "process_support.h"
#include "test_support.h"

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <sys/wait.h>
#include <thread>
#include <fcntl.h>
#include <unistd.h>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>

using namespace talus;

namespace {
const char* kScene = R"(
[simulation]
dx = 0.1
end_time = 0.6
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
# A probe riding the rock (its place is state a checkpoint must keep) and a wave gauge.
[[output.probes]]
name = "rock"
point = [2.2, 0.5, 1.0]
materials = ["rock"]
[[output.gauges]]
name = "pool"
point = [0.5, 0.5]
)";

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

int run(const std::string& args) {
  const std::string cmd = "\"" TALUS_BINARY "\" run " + args + " --quiet --threads 2 > /dev/null 2>&1";
  const int status = std::system(cmd.c_str());
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

/// Starts `talus run scene --out dir` and kills it (SIGKILL, as a machine or a batch system
/// would) as soon as its first checkpoint exists. Returns true when the kill hit a running job.
bool runAndKillAfterCheckpoint(const std::string& scene, const std::string& dir) {
  const pid_t pid = fork();
  if (pid == 0) {
    const int null = open("/dev/null", O_WRONLY);
    dup2(null, 1), dup2(null, 2);
    execl(TALUS_BINARY, TALUS_BINARY, "run", scene.c_str(), "--out", dir.c_str(), "--quiet", "--threads", "2", nullptr);
    _exit(127);
  }
  while (!std::filesystem::exists(dir + "/checkpoint.h5")) {
    int status;
    if (waitpid(pid, &status, WNOHANG) == pid) return false; // ended before any checkpoint
    std::this_thread::sleep_for(std::chrono::milliseconds(2));
  }
  kill(pid, SIGKILL);
  int status;
  waitpid(pid, &status, 0);
  return WIFSIGNALED(status) && WTERMSIG(status) == SIGKILL;
}
} // namespace

TEST(Resume, KilledAfterACheckpointAndResumedEqualsAnUninterruptedRun) {
  const std::string dir = test::tempDir("resume");
  const std::string scene = dir + "/scene.toml";
  std::ofstream(scene) << kScene;
  ASSERT_EQ(run(scene + " --out " + dir + "/straight"), 0);
  // Killed right after its first checkpoint (t >= 0.08 s of 0.6 s).
  ASSERT_TRUE(runAndKillAfterCheckpoint(scene, dir + "/killed"));
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
  // summary.json names every file, those written before the kill too (the soak test found the
  // resumed run listing only its own frames).
  auto fileLists = [](const std::string& summary) {
    std::istringstream in(summary);
    std::string line, lists;
    while (std::getline(in, line))
      if (line.find("\"files\"") != std::string::npos) lists += line.substr(line.find("\"files\"")) + "\n";
    return lists;
  };
  const std::string lists = fileLists(slurp(dir + "/straight/summary.json"));
  EXPECT_NE(lists.find("frames/particles_00000.h5"), std::string::npos) << lists;
  EXPECT_EQ(fileLists(slurp(dir + "/killed/summary.json")), lists);
}

TEST(Resume, ARunExtendedToALaterEndTimeEndsAsARunStraightToItAndOtherPhysicsIsRefusedByKey) {
  // An avalanche that has not stopped at end_time = 0.3 is continued to 0.6 from its last
  // checkpoint (t = 0.24): the scene's hash leaves out the end time (and the frame outputs), so
  // the checkpoint is accepted, and the run ends as one run straight to 0.6, byte for byte.
  const std::string dir = test::tempDir("resume_extend");
  const std::string scene = dir + "/scene.toml";
  std::string text = kScene;
  text.replace(text.find("checkpoint_interval = 0.08\n"), 27, "checkpoint_interval = 0.08\nseries_interval = 0.02\n");
  std::ofstream(scene) << text;
  ASSERT_EQ(run(scene + " --out " + dir + "/straight"), 0);
  ASSERT_EQ(run(scene + " --out " + dir + "/extended --set simulation.end_time=0.3"), 0);
  EXPECT_FALSE(std::filesystem::exists(dir + "/extended/frames/particles_00004.h5"));
  ASSERT_EQ(run(scene + " --resume " + dir + "/extended --set simulation.end_time=0.6"), 0);
  for (const char* file : {"particles.h5", "series.csv", "maps/max_flow_height_vertical.tif", "maps/max_speed.tif",
                           "frames/particles_00006.h5"}) {
    const std::string a = slurp(dir + "/straight/" + file), b = slurp(dir + "/extended/" + file);
    EXPECT_FALSE(a.empty()) << file;
    EXPECT_TRUE(a == b) << file << " differs after the extension";
  }
  // Frames at another interval continue after the checkpoint's time (0.56: the next of 0.05 s is
  // frame 12 at 0.6), not from the old interval's next index.
  ASSERT_EQ(run(scene + " --resume " + dir + "/extended --set output.frame_interval=0.05"), 0);
  EXPECT_TRUE(std::filesystem::exists(dir + "/extended/frames/particles_00012.h5"));
  EXPECT_FALSE(std::filesystem::exists(dir + "/extended/frames/particles_00007.h5"));
  // A key that shapes the state is still refused, and named.
  const test::Exit e = test::runTalusProcess(
      {"run", scene, "--resume", dir + "/extended", "--quiet", "--set", "materials.water.sound_speed=50"}, dir + "/log");
  EXPECT_EQ(e.code, 2) << e.log;
  EXPECT_NE(e.log.find("materials[0].sound_speed (40 there, 50 here) changed since"), std::string::npos) << e.log;
}

TEST(Resume, ResumingWithoutACheckpointIsAClearError) {
  const std::string dir = test::tempDir("resume_missing");
  const std::string scene = dir + "/scene.toml";
  std::ofstream(scene) << kScene;
  EXPECT_EQ(run(scene + " --resume " + dir + "/nowhere"), 2);
}
