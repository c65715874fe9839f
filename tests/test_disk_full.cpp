// A real full disk and a folder turning read-only: the output folder is a small tmpfs mounted
// by the test in its own mount namespace (skipped with a message where mounting is not
// permitted). The run stops with one line naming the file and the cause and exit status 4;
// every file it left is whole; after space is freed the last checkpoint resumes to the
// uninterrupted run's result.
#include "io/run/checkpoint.h"
#include "process_support.h"
#include "test_support.h"
#include "tools/output_check.h"

#include <cstring>
#include <gtest/gtest.h>
#include <sched.h>
#include <sys/mount.h>

using namespace talus;

namespace {

const char* kOutput = "frame_interval = 0.05\ncheckpoint_interval = 0.1\nply = true\nmaps = { cell_size = 0.2 }\n";
const std::string kScene = test::rockThrowScene("0.6", "0.3", kOutput);

/// A tmpfs at `dir`, visible to this process and its children only.
class Tmpfs {
public:
  Tmpfs(const std::string& dir, size_t bytes) : dir_(dir) {
    // Needs CAP_SYS_ADMIN and a single-threaded process (ctest runs each test alone).
    if (unshare(CLONE_NEWNS) != 0) {
      why_ = std::string("cannot make a private mount namespace: ") + std::strerror(errno);
      return;
    }
    if (mount("none", "/", nullptr, MS_REC | MS_PRIVATE, nullptr) != 0 ||
        mount("tmpfs", dir.c_str(), "tmpfs", 0, ("size=" + std::to_string(bytes)).c_str()) != 0) {
      why_ = std::string("cannot mount a tmpfs: ") + std::strerror(errno);
      return;
    }
    mounted_ = true;
  }
  ~Tmpfs() {
    if (mounted_) umount2(dir_.c_str(), MNT_DETACH);
  }
  const std::string& whyNot() const { return why_; }
  bool mounted() const { return mounted_; }
  bool remount(const std::string& options, unsigned long flags = 0) {
    return mount("tmpfs", dir_.c_str(), "tmpfs", MS_REMOUNT | flags, options.c_str()) == 0;
  }

private:
  std::string dir_, why_;
  bool mounted_ = false;
};

size_t folderBytes(const std::string& dir) {
  size_t n = 0;
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir))
    if (e.is_regular_file()) n += e.file_size();
  return n;
}

std::vector<std::string> runArgs(const std::string& dir, const std::string& out) {
  return {"run", dir + "/scene.toml", "--out", out, "--quiet", "--threads", "2"};
}

void expectSameResult(const std::string& a, const std::string& b) {
  for (const char* f : {"particles.h5", "series.csv", "maps/max_speed.tif", "frames/particles_00012.h5"})
    EXPECT_TRUE(test::slurp(a + "/" + f) == test::slurp(b + "/" + f)) << f << " differs after resume";
}

} // namespace

TEST(DiskFull, ARunFillingATmpfsStopsAndResumesOnceSpaceIsFreed) {
  const std::string dir = test::tempDir("disk_full");
  std::ofstream(dir + "/scene.toml") << kScene;
  const test::Exit s = test::runTalusProcess(runArgs(dir, dir + "/straight"), dir + "/straight.log");
  ASSERT_EQ(s.code, 0) << s.log;
  const size_t total = folderBytes(dir + "/straight");
  const size_t checkpoint = std::filesystem::file_size(dir + "/straight/checkpoint.h5");

  // Room for about half of the outputs, and for two checkpoints at once (old and temporary).
  const size_t room = std::max(total / 2, 3 * checkpoint);
  std::filesystem::create_directories(dir + "/disk");
  Tmpfs disk(dir + "/disk", room);
  if (!disk.mounted()) GTEST_SKIP() << disk.whyNot() << " (run as root, alone: ctest does)";
  const std::string out = dir + "/disk/out";
  const test::Exit e = test::runTalusProcess(runArgs(dir, out), dir + "/full.log");
  EXPECT_EQ(e.code, 4) << e.log;
  ASSERT_EQ(e.lines().size(), 1u) << e.log;
  EXPECT_EQ(e.lines()[0].rfind("talus: error: cannot write " + out + "/", 0), 0u) << e.log;
  EXPECT_NE(e.log.find(": No space left on device"), std::string::npos) << e.log;
  EXPECT_NE(e.log.find("--resume " + out), std::string::npos) << e.log; // a checkpoint was written before
  EXPECT_EQ(incompleteOutputFiles(out), std::vector<std::string>{});
  EXPECT_NO_THROW(inspectCheckpoint(out + "/checkpoint.h5"));

  ASSERT_TRUE(disk.remount("size=" + std::to_string(4 * total)));
  const test::Exit r = test::runTalusProcess({"run", dir + "/scene.toml", "--resume", out, "--quiet"}, dir + "/r.log");
  ASSERT_EQ(r.code, 0) << r.log;
  expectSameResult(dir + "/straight", out);
}

TEST(DiskFull, AFolderTurnedReadOnlyMidRunIsNamedAndTheCheckpointKept) {
  const std::string dir = test::tempDir("disk_readonly");
  const std::string slow = test::rockThrowScene("6.0", "0.3", kOutput);
  std::ofstream(dir + "/scene.toml") << slow;
  std::filesystem::create_directories(dir + "/disk");
  Tmpfs disk(dir + "/disk", size_t(256) << 20);
  if (!disk.mounted()) GTEST_SKIP() << disk.whyNot() << " (run as root, alone: ctest does)";
  const std::string out = dir + "/disk/out";
  test::TalusProcess p(runArgs(dir, out), dir + "/log");
  ASSERT_TRUE(p.waitForFile(out + "/checkpoint.h5"));
  // A remount fails (EBUSY) while a file is open for writing: retry between writes.
  bool readOnly = false;
  for (int i = 0; i < 2000 && !readOnly; ++i) {
    readOnly = disk.remount("", MS_RDONLY);
    if (!readOnly) std::this_thread::sleep_for(std::chrono::milliseconds(1));
  }
  ASSERT_TRUE(readOnly) << std::strerror(errno);
  const test::Exit e = p.wait();
  EXPECT_EQ(e.code, 4) << e.log;
  ASSERT_EQ(e.lines().size(), 1u) << e.log;
  EXPECT_NE(e.log.find("cannot write " + out + "/"), std::string::npos) << e.log;
  EXPECT_NE(e.log.find(": Read-only file system"), std::string::npos) << e.log;
  EXPECT_EQ(incompleteOutputFiles(out), std::vector<std::string>{});
  EXPECT_NO_THROW(inspectCheckpoint(out + "/checkpoint.h5"));
}
