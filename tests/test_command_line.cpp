// `talus run` as a user types it: options that make no sense are refused with one line.
#include "test_support.h"

#include <gtest/gtest.h>

using talus::test::runTalus;

TEST(CommandLine, ZeroThreadsIsRefusedNotTakenAsAll) {
  // Review defect: --threads 0 was accepted silently (and meant "all").
  std::string out;
  EXPECT_NE(runTalus("run --threads 0 --out " + talus::test::tempDir("threads0"), out), 0);
  EXPECT_NE(out.find("--threads"), std::string::npos) << out;
}
