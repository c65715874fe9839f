// `talus run` as a user types it: options that make no sense are refused with one line.
#include "io/run/run_driver.h"
#include "test_support.h"

#include <type_traits>

#include <gtest/gtest.h>

using talus::test::runTalus;

TEST(CommandLine, ZeroThreadsIsRefusedNotTakenAsAll) {
  // Review defect: --threads 0 was accepted silently (and meant "all").
  std::string out;
  EXPECT_NE(runTalus("run --threads 0 --out " + talus::test::tempDir("threads0"), out), 0);
  EXPECT_NE(out.find("--threads"), std::string::npos) << out;
}

// Review defect: runScene took the scene by reference and silently moved its material groups
// out. It now takes it by rvalue, so a caller must hand the scene over with std::move.
static_assert(!std::is_invocable_v<decltype(&talus::runScene), talus::SceneSetup&, const talus::RunOptions&>,
              "runScene must not accept an lvalue scene");
static_assert(std::is_invocable_v<decltype(&talus::runScene), talus::SceneSetup&&, const talus::RunOptions&>);
