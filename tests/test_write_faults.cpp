// Write failures: a full device (a temporary file symlinked to /dev/full, ENOSPC on every write,
// even as root), a file-size limit (EFBIG; before the fix a failed HDF5 close crashed Talus at
// exit), a removed output folder and a writer that fails on purpose. Each stops the run with
// one line naming the file and the cause and exit status 4, leaves every earlier file whole and
// the last checkpoint resumable to the same result as an uninterrupted run.
#include "io/common/atomic_file.h"
#include "process_support.h"
#include "test_support.h"
#include "tools/output_check.h"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <unistd.h>

using namespace talus;

namespace {

const char* kOutput = "frame_interval = 0.1\ncheckpoint_interval = 0.08\nply = true\nmaps = { cell_size = 0.2 }\n";
const std::string kScene = test::rockThrowScene("0.3", "0.25", kOutput);

std::string writeScene(const std::string& dir) {
  std::ofstream(dir + "/scene.toml") << kScene;
  return dir + "/scene.toml";
}

std::vector<std::string> runArgs(const std::string& scene, const std::string& out) {
  return {"run", scene, "--out", out, "--quiet", "--threads", "2"};
}

/// The uninterrupted run every faulty one is compared with (run once).
const std::string& straightRun() {
  static const std::string dir = [] {
    // Per process: ctest runs the parameterised cases of this file in parallel processes.
    const std::string d = test::tempDir("write_faults_straight_" + std::to_string(::getpid()));
    const test::Exit e = test::runTalusProcess(runArgs(writeScene(d), d + "/out"), d + "/log");
    EXPECT_EQ(e.code, 0) << e.log;
    return d + "/out";
  }();
  return dir;
}

/// A run that failed to write: every file it left is whole, and when it left a checkpoint, a
/// resume (the fault gone) ends with the uninterrupted run's particles, series and maps.
void expectIntactAndResumable(const std::string& scene, const std::string& out) {
  EXPECT_EQ(incompleteOutputFiles(out), std::vector<std::string>{});
  if (!std::filesystem::exists(out + "/checkpoint.h5")) return;
  const test::Exit e = test::runTalusProcess({"run", scene, "--resume", out, "--quiet"}, out + "/../resume.log");
  ASSERT_EQ(e.code, 0) << e.log;
  for (const char* f : {"particles.h5", "series.csv", "maps/max_speed.tif", "frames/particles_00003.h5"})
    EXPECT_TRUE(test::slurp(straightRun() + "/" + f) == test::slurp(out + "/" + f)) << f << " differs after resume";
}

} // namespace

TEST(WriteFaults, AWriterFailingMidWayLeavesThePreviousFileAndNoTemporary) {
  const std::string dir = test::tempDir("write_faults_writer");
  const std::string path = dir + "/result.csv";
  writeAtomically(path, [](const std::string& tmp) { writeFileBytes(tmp, "first version\n"); });
  try {
    writeAtomically(path, [](const std::string& tmp) {
      writeFileBytes(tmp, "half of the sec");
      throw std::runtime_error("the encoder failed");
    });
    FAIL() << "the failure was swallowed";
  } catch (const WriteError& e) {
    EXPECT_EQ(e.file(), path); // the file the user knows, not the temporary
    EXPECT_EQ(e.cause(), "the encoder failed");
  }
  EXPECT_EQ(test::slurp(path), "first version\n");
  EXPECT_FALSE(std::filesystem::exists(path + ".tmp"));
}

TEST(WriteFaults, TheCauseIsTheSystemsReason) {
  const std::string dir = test::tempDir("write_faults_cause");
  try {
    writeFileBytes(dir + "/no/such/folder/x.csv", "x");
    FAIL();
  } catch (const WriteError& e) {
    EXPECT_EQ(std::string(e.what()), "cannot write " + dir + "/no/such/folder/x.csv: No such file or directory");
  }
  std::filesystem::create_symlink("/dev/full", dir + "/full.csv");
  EXPECT_THROW(writeFileBytes(dir + "/full.csv", std::string(100000, 'x')), WriteError);
}

// Each kind of output in turn meets a full device, from the first frame to the last summary.
class FullDevice : public ::testing::TestWithParam<const char*> {};

TEST_P(FullDevice, StopsWithOneLineKeepsEarlierFilesAndResumes) {
  const std::string file = GetParam();
  std::string safe = file;
  std::replace(safe.begin(), safe.end(), '/', '_');
  const std::string dir = test::tempDir("full_device_" + safe), out = dir + "/out";
  const std::string scene = writeScene(dir);
  for (const char* sub : {"", "/frames", "/maps", "/plots"}) std::filesystem::create_directories(out + sub);
  std::filesystem::create_symlink("/dev/full", out + "/" + file + ".tmp");

  const test::Exit e = test::runTalusProcess(runArgs(scene, out), dir + "/log");
  EXPECT_EQ(e.code, 4) << e.log;
  ASSERT_EQ(e.lines().size(), 1u) << e.log;
  EXPECT_EQ(e.lines()[0].rfind("talus: error: cannot write " + out + "/" + file + ": No space left on device", 0), 0u)
      << e.log;
  EXPECT_FALSE(std::filesystem::exists(out + "/" + file + ".tmp")); // the failed temporary is gone
  // The run says what happened in summary.json when the disk still takes it.
  if (file != "summary.json") {
    EXPECT_NE(test::slurp(out + "/summary.json").find("\"status\": \"failed: cannot write"), std::string::npos);
  }
  expectIntactAndResumable(scene, out);
}

INSTANTIATE_TEST_SUITE_P(EveryOutput, FullDevice,
                         ::testing::Values("frames/particles_00000.h5", "checkpoint.h5", "frames/particles_00002.h5",
                                           "frames/volume_00001.vdb", "frames/particles_00002.ply", "series.csv",
                                           "maps/max_speed.tif", "maps/max_speed.png", "plots/kinetic_energy.png",
                                           "particles.h5", "summary.json"),
                         [](const auto& info) {
                           std::string n = info.param;
                           for (char& c : n)
                             if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
                           return n;
                         });

// The reported crash: a checkpoint meeting a file-size limit halfway. HDF5's failed close left a
// dangling file that its exit handler closed again: a segmentation fault (exit 139).
TEST(WriteFaults, AFileSizeLimitInsideACheckpointIsAnErrorNotACrash) {
  const std::string dir = test::tempDir("write_faults_fsize"), out = dir + "/out";
  const std::string scene = writeScene(dir);
  const test::Exit e = test::runTalusProcess(runArgs(scene, out), dir + "/log", [] {
    signal(SIGXFSZ, SIG_IGN); // then write(2) fails with EFBIG instead of killing the process
    const rlimit limit{120 * 1024, 120 * 1024};
    setrlimit(RLIMIT_FSIZE, &limit);
  });
  EXPECT_EQ(e.signal, 0) << "killed by signal " << e.signal;
  EXPECT_EQ(e.code, 4) << e.log;
  ASSERT_EQ(e.lines().size(), 1u) << e.log;
  EXPECT_NE(e.log.find("cannot write " + out + "/checkpoint.h5: File too large"), std::string::npos) << e.log;
  expectIntactAndResumable(scene, out);
}

TEST(WriteFaults, AnOutputFolderRemovedDuringTheRunIsNamed) {
  const std::string dir = test::tempDir("write_faults_removed"), out = dir + "/out";
  const std::string slow = test::rockThrowScene("3.0", "0.25", kOutput);
  std::ofstream(dir + "/scene.toml") << slow;
  test::TalusProcess p(runArgs(dir + "/scene.toml", out), dir + "/log");
  ASSERT_TRUE(p.waitForFile(out + "/frames/particles_00001.h5"));
  // As `rm -rf` would: a file Talus creates meanwhile makes one pass fail (not empty), so retry.
  std::error_code ec;
  for (int i = 0; i < 100 && (std::filesystem::remove_all(out + "/frames", ec), ec); ++i)
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  ASSERT_FALSE(ec) << ec.message();
  const test::Exit e = p.wait();
  EXPECT_EQ(e.code, 4) << e.log;
  ASSERT_EQ(e.lines().size(), 1u) << e.log;
  EXPECT_NE(e.log.find("cannot write " + out + "/frames/"), std::string::npos) << e.log;
  EXPECT_NE(e.log.find(": No such file or directory"), std::string::npos) << e.log;
  EXPECT_EQ(incompleteOutputFiles(out), std::vector<std::string>{});
}

TEST(WriteFaults, AnOutputFolderThatCannotBeCreatedIsNamed) {
  const std::string dir = test::tempDir("write_faults_notdir");
  std::ofstream(dir + "/file") << "a file where the output folder should go\n";
  const test::Exit e = test::runTalusProcess(runArgs(writeScene(dir), dir + "/file/out"), dir + "/log");
  EXPECT_EQ(e.code, 4) << e.log;
  ASSERT_EQ(e.lines().size(), 1u) << e.log;
  EXPECT_NE(e.log.find("cannot write " + dir + "/file/out: Not a directory"), std::string::npos) << e.log;
}
