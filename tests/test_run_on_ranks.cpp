// `mpirun -np N talus run`: the files are one process's, a run checkpointed at N ranks resumes
// at M, and a killed rank ends the job with the last checkpoint intact. Skipped without mpirun.
#include "small_collapse.h"
#include "process_support.h"
#include "test_support.h"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>

using namespace talus;
namespace fs = std::filesystem;

namespace {

/// `mpirun --oversubscribe -np n` with Open MPI's allow-run-as-root variables (CI runs as root).
std::string mpirun(int n) {
  return "OMPI_ALLOW_RUN_AS_ROOT=1 OMPI_ALLOW_RUN_AS_ROOT_CONFIRM=1 mpirun --oversubscribe -np " + std::to_string(n) + " ";
}

bool haveMpirun() {
  std::string out;
  return test::shell("command -v mpirun", out) == 0;
}

std::string bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

/// Every file of a against b's, except those that differ between two one-process runs too
/// (summary.json's wall times and report.html, which shows them; a VDB file's unique id).
void expectSameFiles(const std::string& a, const std::string& b) {
  size_t compared = 0;
  for (const auto& e : fs::recursive_directory_iterator(a)) {
    if (!e.is_regular_file()) continue;
    const fs::path rel = fs::relative(e.path(), a);
    if (rel == "summary.json" || rel == "report.html" || rel.extension() == ".vdb") continue;
    ASSERT_TRUE(fs::exists(fs::path(b) / rel)) << rel;
    EXPECT_TRUE(bytes(e.path()) == bytes(fs::path(b) / rel)) << rel << " differs";
    ++compared;
  }
  EXPECT_GT(compared, 10u);
}

/// `text` with "key = old" replaced by "key = value".
std::string with(std::string text, const std::string& from, const std::string& to) {
  return text.replace(text.find(from), from.size(), to);
}

// The small collapse to 0.12 s, with frames and a checkpoint every 0.01 s: about two seconds.
const std::string kScene = with(test::kSmallCollapse, "end_time = 1", "end_time = 0.12") + R"(
[output]
frame_interval = 0.04
checkpoint_interval = 0.01
)";
std::string sceneFile(const std::string& dir) {
  const std::string f = dir + "/collapse.toml";
  std::ofstream(f) << kScene;
  return f;
}

} // namespace

TEST(RunOnRanks, TheDefaultScenesFilesAtTwoRanksAreOneProcesss) {
  if (!haveMpirun()) GTEST_SKIP() << "mpirun not installed";
  const std::string dir = test::tempDir("ranks_default");
  std::string out;
  ASSERT_EQ(test::runTalus("run --quiet --set simulation.end_time=1.5 --threads 1 --out " + dir + "/one", out), 0) << out;
  ASSERT_EQ(test::shell(mpirun(2) + TALUS_BINARY " run --quiet --set simulation.end_time=1.5 --threads 1 --out " + dir + "/two", out), 0) << out;
  expectSameFiles(dir + "/one", dir + "/two");
  const std::string summary = bytes(dir + "/two/summary.json");
  EXPECT_NE(summary.find("\"ranks\": 2"), std::string::npos);
  EXPECT_NE(summary.find("\"communication_seconds\""), std::string::npos);
}

TEST(RunOnRanks, ARunCheckpointedAtFourRanksResumesAtTwo) {
  if (!haveMpirun()) GTEST_SKIP() << "mpirun not installed";
  const std::string dir = test::tempDir("ranks_resume");
  const std::string scene = sceneFile(dir);
  std::string out;
  ASSERT_EQ(test::runTalus("run " + scene + " --quiet --threads 1 --out " + dir + "/one", out), 0) << out;
  ASSERT_EQ(test::shell(mpirun(4) + TALUS_BINARY " run " + scene + " --quiet --threads 1 --out " + dir + "/four", out), 0) << out;
  expectSameFiles(dir + "/one", dir + "/four");
  // The four ranks' last checkpoint (t = 0.11 s), resumed at two ranks, ends where one process did.
  ASSERT_EQ(test::shell(mpirun(2) + TALUS_BINARY " run " + scene + " --quiet --threads 1 --resume " + dir + "/four", out), 0) << out;
  expectSameFiles(dir + "/one", dir + "/four");
}

TEST(RunOnRanks, AKilledRankEndsTheJobNamingItAndLeavesTheLastCheckpointWhole) {
  if (!haveMpirun()) GTEST_SKIP() << "mpirun not installed";
  const std::string dir = test::tempDir("ranks_killed");
  const std::string scene = sceneFile(dir);
  const std::string run = dir + "/run";
  // Rank 1 is killed (SIGKILL: no handler runs) once the run has written its second checkpoint.
  const std::string cmd = mpirun(2) + "sh -c 'if [ \"$OMPI_COMM_WORLD_RANK\" = 1 ]; then (while [ ! -s " + run +
                          "/checkpoint.h5 ]; do sleep 0.05; done; sleep 0.3; kill -9 $$) & fi; exec " TALUS_BINARY
                          " run " + scene + " --set simulation.end_time=0.3 --threads 1 --out " + run + "'";
  std::string out;
  EXPECT_NE(test::shell(cmd, out), 0);
  EXPECT_NE(out.find("rank 1"), std::string::npos) << out;
  EXPECT_NE(out.find("signal 9"), std::string::npos) << out;
  EXPECT_NE(out.find("the job was at step"), std::string::npos) << out; // rank 0's line, on mpirun's SIGTERM
  // The checkpoint on disk is whole: one process resumes from it to the end.
  std::string resumed;
  ASSERT_EQ(test::runTalus("run " + scene + " --set simulation.end_time=0.3 --quiet --threads 1 --resume " + run, resumed), 0)
      << resumed;
}
