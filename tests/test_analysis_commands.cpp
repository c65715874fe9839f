// The post-processing commands as a user calls them: `talus compare`, `map-stats` and `profile` on
// GeoTIFFs the program writes itself (the library functions behind them are tested in
// test_analysis.cpp; this checks the command-line wiring, which once crashed on `compare --png`).
#include "terrain_test_support.h"

#include <array>
#include <cstdio>
#include <filesystem>
#include <gtest/gtest.h>
#include <string>
#include <sys/wait.h>

namespace fs = std::filesystem;

using talus::test::runTalus;

TEST(AnalysisCommands, CompareOfARasterWithItselfOverlapsCompletelyAndDrawsItsMap) {
  const std::string dir = talus::test::tempDir("analysis_commands");
  const std::string dem = dir + "/dem.tif", png = dir + "/overlap.png";
  std::string out;
  ASSERT_EQ(runTalus("synth-dem slope_valley --cell 20 --out " + dem, out), 0) << out;
  ASSERT_EQ(runTalus("compare " + dem + " " + dem + " --threshold 1000 --png " + png + " --dem " + dem, out), 0) << out;
  // Identical rasters: every cell above the threshold is in both, the bias and rmse are zero.
  EXPECT_NE(out.find(" 1.000 "), std::string::npos) << out;
  EXPECT_TRUE(fs::exists(png));
  ASSERT_EQ(runTalus("map-stats " + dem + " --threshold 1000", out), 0) << out;
  EXPECT_NE(out.find("threshold"), std::string::npos) << out;
  ASSERT_EQ(runTalus("profile " + dem + " --line \"2600100,1200100 2600900,1200100\" --out " + dir + "/p.csv", out), 0)
      << out;
  EXPECT_TRUE(fs::exists(dir + "/p.csv"));
}

TEST(AnalysisCommands, AMissingRasterIsAOneLineErrorNotACrash) {
  std::string out;
  const int rc = runTalus("compare /nonexistent/a.tif /nonexistent/b.asc", out);
  EXPECT_NE(rc, 0);
  EXPECT_LT(rc, 128) << "killed by a signal";
  EXPECT_NE(out.find("/nonexistent/a.tif"), std::string::npos) << out;
}
