// report.html (io/run/run_report.h): one self-contained page per run, checked in headless
// Chromium: its script runs without error and builds the tables from summary.json.
#include "process_support.h"
#include "test_support.h"

#include <filesystem>
#include <gtest/gtest.h>
#include <regex>

using namespace talus;
namespace fs = std::filesystem;

namespace {

const std::string kBinary = TALUS_BINARY;

size_t count(const std::string& text, const std::string& what) {
  size_t n = 0;
  for (size_t p = text.find(what); p != std::string::npos; p = text.find(what, p + 1)) ++n;
  return n;
}

} // namespace

TEST(RunReport, APageOfTheRunThatNeedsNothingElseAndWhoseScriptBuildsItsTables) {
  const std::string dir = test::tempDir("run_report");
  std::string log;
  ASSERT_EQ(test::shell("\"" + kBinary + "\" run --quiet --set simulation.end_time=1 --set output.h5=false "
                        "--set output.vdb=false --out " + dir + "/run", log), 0) << log;
  const std::string page = test::slurp(dir + "/run/report.html");
  ASSERT_FALSE(page.empty());
  // Self-contained: nothing is fetched (pictures and film are data: URIs inside it).
  EXPECT_EQ(count(page, "http://") + count(page, "https://"), 0u);
  EXPECT_EQ(count(page, "\"animation.mp4\": \"data:video/mp4;base64,"), 1u);
  size_t mapPngs = 0;
  for (const auto& e : fs::directory_iterator(dir + "/run/maps")) mapPngs += e.path().extension() == ".png";
  const std::regex embedded("\"maps/[^\"]*\\.png\": \"data:image/png;base64,");
  EXPECT_EQ(size_t(std::distance(std::sregex_iterator(page.begin(), page.end(), embedded), std::sregex_iterator())),
            mapPngs);

  if (test::shell("chromium --version", log) != 0) GTEST_SKIP() << "Chromium is not installed (apt-get install chromium)";
  ASSERT_EQ(test::shell("chromium --headless=new --no-sandbox --disable-gpu --dump-dom file://" + dir +
                        "/run/report.html 2>/dev/null", log), 0);
  EXPECT_NE(log.find("data-ready=\"yes\""), std::string::npos) << "the page's script did not finish";
  EXPECT_NE(log.find("<pre id=\"errors\"></pre>"), std::string::npos) << "script errors: " << log.substr(0, 2000);
  // The run table holds summary.json's step count, and every map quick-look is a figure.
  const std::string summary = test::slurp(dir + "/run/summary.json");
  std::smatch steps;
  ASSERT_TRUE(std::regex_search(summary, steps, std::regex("\"steps\": ([0-9]+)")));
  EXPECT_NE(log.find("<td>steps</td><td class=\"num\">" + steps[1].str() + "</td>"), std::string::npos);
  EXPECT_EQ(count(log, "<figcaption>maps/"), mapPngs);
  EXPECT_NE(log.find("<video src=\"data:video/mp4;base64,"), std::string::npos);
}

TEST(RunReport, ReportFalseWritesNone) {
  const std::string dir = test::tempDir("run_report_off");
  std::string log;
  ASSERT_EQ(test::shell("\"" + kBinary + "\" run --quiet --set simulation.end_time=0.05 --set output.report=false "
                        "--set output.animation=false --out " + dir, log), 0) << log;
  EXPECT_FALSE(fs::exists(dir + "/report.html"));
  EXPECT_TRUE(fs::exists(dir + "/summary.json"));
}

TEST(RunReport, AnEnsemblesPageListsItsMembersInATableThatSorts) {
  const std::string dir = test::tempDir("ensemble_report");
  std::string log;
  ASSERT_EQ(test::shell("\"" + kBinary + "\" ensemble " + TALUS_SOURCE_DIR + "/data/scenes/default.toml --vary "
                        "terrain.friction=0.3:0.5 --samples 2 --jobs 2 --set simulation.end_time=0.5 --out " + dir, log), 0)
      << log;
  const std::string page = test::slurp(dir + "/report.html");
  ASSERT_FALSE(page.empty());
  EXPECT_NE(page.find("\"kind\": \"ensemble\""), std::string::npos);
  EXPECT_NE(page.find("\"terrain.friction\": 0.3"), std::string::npos); // members.csv as numbers
  if (test::shell("chromium --version", log) != 0) GTEST_SKIP() << "Chromium is not installed (apt-get install chromium)";
  ASSERT_EQ(test::shell("chromium --headless=new --no-sandbox --disable-gpu --dump-dom file://" + dir +
                        "/report.html 2>/dev/null", log), 0);
  EXPECT_NE(log.find("data-ready=\"yes\""), std::string::npos) << "the page's script did not finish";
  EXPECT_NE(log.find("<pre id=\"errors\"></pre>"), std::string::npos) << "script errors: " << log.substr(0, 2000);
  EXPECT_NE(log.find("2 of 2 members completed"), std::string::npos);
  const size_t table = log.find("id=\"member-table\"");
  ASSERT_NE(table, std::string::npos);
  EXPECT_EQ(count(log.substr(table, log.find("</table>", table) - table), "<tr>"), 3u); // header and two members
}
