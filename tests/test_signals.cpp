// Signals a long run meets: SIGINT and SIGTERM finish the step, write a checkpoint and a
// summary.json saying "interrupted" at the step reached, and exit with 130 / 143; the resumed
// run ends as an uninterrupted one. A second signal ends the process at once. SIGUSR1 writes a
// checkpoint and the run goes on.
#include "process_support.h"
#include "test_support.h"
#include "tools/output_check.h"

#include <gtest/gtest.h>
#include <regex>

using namespace talus;

namespace {

// About 3 s on two threads when left alone: long enough to be interrupted after a frame.
const char* kOutput = "frame_interval = 0.25\ncheckpoint_interval = 0\nvdb = false\nmaps = { cell_size = 0.2 }\n";
const std::string kScene = test::rockThrowScene("2", "0.25", kOutput);

std::string setUp(const std::string& name) {
  const std::string dir = test::tempDir(name);
  std::ofstream(dir + "/scene.toml") << kScene;
  return dir;
}

std::vector<std::string> runArgs(const std::string& dir, const std::string& out) {
  return {"run", dir + "/scene.toml", "--out", out, "--threads", "2"};
}

double jsonNumber(const std::string& json, const std::string& key) {
  std::smatch m;
  if (!std::regex_search(json, m, std::regex("\"" + key + "\": ([-0-9.e+]+)"))) return -1;
  return std::stod(m[1]);
}

/// Stops a run with `sig` once its first frame after the start is written; checks what it left.
void interruptAndResume(int sig, int expectedCode, const std::string& name) {
  const std::string dir = setUp(name), out = dir + "/out";
  test::TalusProcess p(runArgs(dir, out), dir + "/log");
  ASSERT_TRUE(p.waitForFile(out + "/frames/particles_00001.h5"));
  p.signal(sig);
  const test::Exit e = p.wait();
  ASSERT_EQ(e.code, expectedCode) << e.log;
  const std::string summary = test::slurp(out + "/summary.json");
  EXPECT_NE(summary.find("\"status\": \"interrupted\""), std::string::npos) << summary;
  EXPECT_NE(summary.find(std::string("\"interrupted_by\": \"") + (sig == SIGINT ? "SIGINT" : "SIGTERM")),
            std::string::npos);
  const double t = jsonNumber(summary, "simulated_time");
  const double steps = jsonNumber(summary, "steps");
  EXPECT_GT(t, 0.25); // after the frame it waited for...
  EXPECT_LT(t, 2.0);  // ...and before the end
  // The last line names the step and how to continue.
  const std::string last = e.lines().back();
  EXPECT_NE(last.find("interrupted by " + std::string(sig == SIGINT ? "SIGINT" : "SIGTERM") + " at step " +
                      std::to_string(uint64_t(steps))),
            std::string::npos) << last;
  EXPECT_NE(last.find("--resume " + out), std::string::npos) << last;
  EXPECT_FALSE(std::filesystem::exists(out + "/particles.h5")); // the final state is not reached
  EXPECT_EQ(incompleteOutputFiles(out), std::vector<std::string>{});

  // Resumed from the step it stopped at, it ends as the uninterrupted run does.
  const test::Exit r = test::runTalusProcess({"run", dir + "/scene.toml", "--resume", out, "--quiet"}, dir + "/resume.log");
  ASSERT_EQ(r.code, 0) << r.log;
  EXPECT_NE(test::slurp(out + "/summary.json").find("\"status\": \"completed\""), std::string::npos);
  const test::Exit s = test::runTalusProcess({"run", dir + "/scene.toml", "--out", dir + "/straight", "--quiet"}, dir + "/s.log");
  ASSERT_EQ(s.code, 0) << s.log;
  for (const char* f : {"particles.h5", "series.csv", "maps/max_speed.tif", "frames/particles_00007.h5"})
    EXPECT_TRUE(test::slurp(dir + "/straight/" + f) == test::slurp(out + "/" + f)) << f << " differs after resume";
}

} // namespace

TEST(Signals, SigtermFinishesTheStepCheckpointsAndExits143) { interruptAndResume(SIGTERM, 143, "signals_term"); }

TEST(Signals, SigintFinishesTheStepCheckpointsAndExits130) { interruptAndResume(SIGINT, 130, "signals_int"); }

TEST(Signals, ASecondSignalEndsTheProcessAtOnce) {
  const std::string dir = setUp("signals_twice"), out = dir + "/out";
  test::TalusProcess p(runArgs(dir, out), dir + "/log");
  ASSERT_TRUE(p.waitForFile(out + "/frames/particles_00001.h5"));
  // Both arrive while the process is stopped, so the second is handled before any step ends.
  p.signal(SIGSTOP);
  p.signal(SIGINT);
  p.signal(SIGTERM);
  p.signal(SIGCONT);
  const test::Exit e = p.wait();
  // Either may be handled first (they can reach two threads at once); the other ends it.
  EXPECT_TRUE(e.signal == SIGTERM || e.signal == SIGINT) << "exit code " << e.code << "\n" << e.log;
  EXPECT_FALSE(std::filesystem::exists(out + "/summary.json")); // it did not stay to write one
  EXPECT_FALSE(std::filesystem::exists(out + "/checkpoint.h5"));
}

TEST(Signals, Sigusr1WritesACheckpointAndTheRunGoesOn) {
  const std::string dir = setUp("signals_usr1"), out = dir + "/out";
  test::TalusProcess p(runArgs(dir, out), dir + "/log");
  ASSERT_TRUE(p.waitForFile(out + "/frames/particles_00001.h5"));
  EXPECT_FALSE(std::filesystem::exists(out + "/checkpoint.h5")); // checkpoint_interval = 0: none on its own
  p.signal(SIGUSR1);
  ASSERT_TRUE(p.waitForFile(out + "/checkpoint.h5", 30)) << "no checkpoint after SIGUSR1";
  const test::Exit e = p.wait();
  EXPECT_EQ(e.code, 0) << e.log;
  EXPECT_NE(test::slurp(out + "/summary.json").find("\"status\": \"completed\""), std::string::npos);
  EXPECT_TRUE(std::filesystem::exists(out + "/particles.h5"));
  EXPECT_EQ(incompleteOutputFiles(out), std::vector<std::string>{});
}
