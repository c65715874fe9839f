// Ensembles (hazard/ensemble_*, `talus ensemble`): --vary parsing and its one-line errors, the
// three samplings, per-cell statistics, a two-parameter ensemble of a small scene whose maps are
// recomputed here from its members' peak files, and a re-run after a killed member.
#include "hazard/ensemble_aggregate.h"
#include "hazard/ensemble_plan.h"
#include "hazard/ensemble_runner.h"
#include "process_support.h"
#include "terrain_test_support.h"
#include "tools/analysis.h"

#include <chrono>
#include <csignal>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <set>
#include <sstream>
#include <thread>

using namespace talus;
using namespace talus::ensemble;
namespace fs = std::filesystem;

namespace {

/// A 3 m slab on the synthetic slope, coarse (dx 10 m: a few hundred particles): seconds a member.
std::string writeScene(const std::string& dir, double endTime) {
  const std::string path = dir + "/scene.toml";
  std::ofstream(path) << R"(
[simulation]
dx = 10.0
end_time = )" << endTime << R"(
[terrain]
synthetic = { kind = "slope_valley", cell_size = 20.0 }
friction = 0.3
[domain]
walls = "open"
[[materials]]
name = "snow"
preset = "snow"
[[bodies]]
name = "slab"
kind = "release"
material = "snow"
bounds = [2600250.0, 1200350.0, 2600400.0, 1200450.0]
thickness = 3.0
[output]
maps = true
plots = false
checkpoint_interval = 0.5
[ensemble]
thresholds = { pft = [0.5], ppr = [1.0] }
runout_result = "pft"
runout_threshold = 0.1
path = [[2600100.0, 1200400.0], [2601300.0, 1200400.0]]
)";
  return path;
}

std::string errorOf(const std::function<void()>& f) {
  try {
    f();
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

DemRaster constant(std::vector<float> v) {
  DemRaster r;
  r.grid.nx = int(v.size()), r.grid.ny = 1;
  r.height = std::move(v);
  return r;
}

size_t lines(const std::string& s) {
  size_t n = 0;
  for (char c : s) n += c == '\n';
  return n;
}

} // namespace

TEST(Ensemble, VarySpecificationsAreCheckedOneLineEach) {
  const VarySpec v = parseVary("terrain.friction=0.15:0.25");
  EXPECT_EQ(v.key, "terrain.friction");
  EXPECT_DOUBLE_EQ(v.low, 0.15);
  EXPECT_DOUBLE_EQ(v.high, 0.25);
  EXPECT_DOUBLE_EQ(parseVary("a.b=-1e-3:2").low, -1e-3);
  EXPECT_NE(errorOf([] { parseVary("terrain.friction"); }).find("KEY=LOW:HIGH"), std::string::npos);
  EXPECT_NE(errorOf([] { parseVary("terrain.friction=0.2"); }).find("one ':'"), std::string::npos);
  EXPECT_NE(errorOf([] { parseVary("terrain.friction=a:0.2"); }).find("'a' is not a number"), std::string::npos);
  EXPECT_NE(errorOf([] { parseVary("terrain.friction=0.2:"); }).find("'' is not a number"), std::string::npos);
  EXPECT_NE(errorOf([] { parseVary("terrain.friction=0.3:0.2"); }).find("empty range"), std::string::npos);
  EXPECT_NE(errorOf([] { parseVary("terrain.friction=0.2:0.2"); }).find("empty range"), std::string::npos);
  EXPECT_NE(errorOf([] { parseVaries({"a.b=0:1", "a.b=1:2"}); }).find("twice"), std::string::npos);
  EXPECT_NE(errorOf([] { parseMethod("sobol"); }).find("lhs, grid, morris"), std::string::npos);
}

TEST(Ensemble, BadVaryOnTheCommandLineStopsBeforeAnyMemberRuns) {
  test::useTestTerrainCache();
  const std::string dir = test::tempDir("ensemble_badvary");
  const std::string scene = writeScene(dir, 1.0);
  for (const auto& [spec, expect] : std::vector<std::pair<std::string, std::string>>{
           {"simulation.dxx=5:10", "unknown key"},
           {"terrain.friction=0.4:0.2", "empty range"},
           {"terrain.friction=low:0.2", "not a number"},
           {"materials.snow.preset=1:2", "expected a string"}}) {
    std::string out;
    const int rc = test::runTalus("ensemble " + scene + " --vary " + spec + " --samples 2 --out " + dir + "/ens", out);
    EXPECT_EQ(rc, 2) << spec << ": " << out;
    EXPECT_NE(out.find(expect), std::string::npos) << spec << ": " << out;
    EXPECT_NE(out.find(spec), std::string::npos) << "names the --vary: " << out;
    EXPECT_EQ(lines(out), 1u) << out;
    EXPECT_FALSE(fs::exists(dir + "/ens/member_000")) << spec;
  }
}

TEST(Ensemble, LatinHypercubePutsOneMemberInEveryStratumOfEveryKey) {
  const auto vary = parseVaries({"a.x=0:10", "a.y=-1:1"});
  const Plan p = makePlan(vary, Method::Lhs, 16, 7);
  ASSERT_EQ(p.members(), 16u);
  for (size_t k = 0; k < 2; ++k) {
    std::set<int> strata;
    for (size_t m = 0; m < 16; ++m) strata.insert(int(p.unit[m][k] * 16));
    EXPECT_EQ(strata.size(), 16u) << "key " << k;
  }
  for (size_t m = 0; m < 16; ++m) {
    const double y = std::stod(p.values[m][1]);
    EXPECT_GE(y, -1.0);
    EXPECT_LE(y, 1.0);
  }
  EXPECT_EQ(makePlan(vary, Method::Lhs, 16, 7).csv(), p.csv()) << "seeded: reproducible";
  EXPECT_NE(makePlan(vary, Method::Lhs, 16, 8).csv(), p.csv());
  EXPECT_EQ(p.overrides(3).at(0), "a.x=" + p.values[3][0]);
}

TEST(Ensemble, GridTakesEveryCombinationOfTheLevels) {
  const Plan p = makePlan(parseVaries({"a.x=0:1", "a.y=10:20"}), Method::Grid, 3, 0);
  ASSERT_EQ(p.members(), 9u);
  EXPECT_EQ(p.values[0], (std::vector<std::string>{"0", "10"}));
  EXPECT_EQ(p.values[1], (std::vector<std::string>{"0", "15"}));
  EXPECT_EQ(p.values[8], (std::vector<std::string>{"1", "20"}));
}

TEST(Ensemble, MorrisTrajectoriesMoveOneKeyAStepAndRecoverLinearEffects) {
  const auto vary = parseVaries({"a.x=0:1", "a.y=0:1", "a.z=0:1"});
  const Plan p = makePlan(vary, Method::Morris, 5, 3);
  ASSERT_EQ(p.members(), 5u * 4u);
  for (size_t r = 0; r < 5; ++r)
    for (size_t s = 0; s < 3; ++s) {
      const auto& a = p.unit[r * 4 + s];
      const auto& b = p.unit[r * 4 + s + 1];
      int moved = 0;
      for (size_t k = 0; k < 3; ++k) {
        if (a[k] != b[k]) {
          ++moved;
          EXPECT_NEAR(b[k] - a[k], 2.0 / 3.0, 1e-12);
        }
        EXPECT_GE(b[k], 0.0);
        EXPECT_LE(b[k], 1.0 + 1e-12);
      }
      EXPECT_EQ(moved, 1);
    }
  // y = 3 x - 2 y (+ 0 z): elementary effects are exactly 3, -2 and 0, with no spread.
  std::vector<double> y;
  for (const auto& u : p.unit) y.push_back(3 * u[0] - 2 * u[1]);
  const auto e = morrisEffects(p, y);
  EXPECT_NEAR(e[0].muStar, 3, 1e-12);
  EXPECT_NEAR(e[1].mu, -2, 1e-12);
  EXPECT_NEAR(e[1].muStar, 2, 1e-12);
  EXPECT_NEAR(e[2].muStar, 0, 1e-12);
  EXPECT_NEAR(e[0].sigma, 0, 1e-12);
  EXPECT_EQ(e[0].effects, 5u);
  // A failed member (NaN) drops the effects it takes part in, nothing else.
  y[1] = NAN;
  size_t total = 0;
  for (const auto& x : morrisEffects(p, y)) total += x.effects;
  EXPECT_EQ(total, 15u - 2u);
}

TEST(Ensemble, CellStatisticsOverMembers) {
  const DemRaster a = constant({0, 1, 2, NAN}), b = constant({0, 3, 2, NAN}), c = constant({1, 5, NAN, NAN});
  const std::vector<const DemRaster*> m{&a, &b, &c};
  const auto p = exceedanceProbability(m, 1.0); // strictly above, as AvaFrame's probAna
  EXPECT_FLOAT_EQ(p[0], 0.f);
  EXPECT_FLOAT_EQ(p[1], 2.f / 3.f);
  EXPECT_FLOAT_EQ(p[2], 1.f); // of the members with data there
  EXPECT_TRUE(std::isnan(p[3]));
  EXPECT_FLOAT_EQ(cellMean(m)[1], 3.f);
  EXPECT_FLOAT_EQ(cellQuantile(m, 0.5)[1], 3.f);
  EXPECT_FLOAT_EQ(cellQuantile(m, 0.25)[1], 2.f); // position 0.5 between 1 and 3
  EXPECT_FLOAT_EQ(cellQuantile(m, 1.0)[1], 5.f);
}

TEST(Ensemble, ProbabilityMapIsWhatTheMembersPeakFilesGive) {
  test::useTestTerrainCache();
  const std::string dir = test::tempDir("ensemble_grid");
  const std::string scene = writeScene(dir, 3.0);
  std::string out;
  // Two keys, two levels each: four members, two at a time.
  ASSERT_EQ(test::runTalus("ensemble " + scene + " --vary terrain.friction=0.2:0.5 --vary bodies.slab.thickness=2:4 "
                           "--samples 2 --method grid --jobs 2 --out " + dir + "/ens",
                           out),
            0)
      << out;
  const std::string ens = dir + "/ens";
  std::vector<DemRaster> pft, ppr;
  for (size_t m = 0; m < 4; ++m) {
    const std::string md = ens + "/" + memberName(m);
    ASSERT_EQ(memberState(md), MemberState::Completed) << md;
    pft.push_back(analysis::readRaster(findPeakFile(md, "pft")));
    ppr.push_back(analysis::readRaster(findPeakFile(md, "ppr")));
  }
  // P(pft > 0.5 m) and P(ppr > 1 kPa) per cell: k of 4 members, exact in float32.
  for (const auto& [members, file, lim] : {std::make_tuple(&pft, "prob_pft_lim0.5.tif", 0.5),
                                           std::make_tuple(&ppr, "prob_ppr_lim1.tif", 1.0)}) {
    const DemRaster prob = analysis::readRaster(ens + "/maps/" + file);
    size_t between = 0;
    for (size_t c = 0; c < prob.height.size(); ++c) {
      int k = 0, n = 0;
      for (const auto& r : *members)
        if (std::isfinite(r.height[c])) ++n, k += r.height[c] > lim;
      if (n == 0) {
        EXPECT_TRUE(std::isnan(prob.height[c])) << file << " cell " << c;
        continue;
      }
      EXPECT_EQ(prob.height[c], float(double(k) / n)) << file << " cell " << c;
      between += k > 0 && k < n;
    }
    EXPECT_GT(between, 0u) << file << ": the members differ somewhere";
  }
  // The median of four is the mean of the middle two.
  const DemRaster q50 = analysis::readRaster(ens + "/maps/q50_pft.tif");
  for (size_t c = 0; c < q50.height.size(); c += 7) {
    std::vector<float> v;
    for (const auto& r : pft)
      if (std::isfinite(r.height[c])) v.push_back(r.height[c]);
    if (v.size() != 4) continue;
    std::sort(v.begin(), v.end());
    EXPECT_NEAR(q50.height[c], 0.5 * (double(v[1]) + v[2]), 1e-6 * std::max(1.0f, v[2])) << c;
  }
  // One CSV row per member with its values; AvaFrame sees the ensemble as one peakFiles folder.
  std::ifstream csv(ens + "/members.csv");
  std::string header, row;
  std::getline(csv, header);
  EXPECT_EQ(header.rfind("member,terrain.friction,bodies.slab.thickness,status", 0), 0u) << header;
  size_t rows = 0;
  while (std::getline(csv, row)) rows += row.find(",completed,") != std::string::npos;
  EXPECT_EQ(rows, 4u);
  std::set<std::string> names;
  for (const auto& e : fs::directory_iterator(ens + "/peakFiles")) names.insert(e.path().filename().string());
  EXPECT_EQ(names.size(), 16u);
  EXPECT_TRUE(fs::exists(ens + "/runout.png"));
  EXPECT_TRUE(fs::exists(ens + "/maps/prob_pft_lim0.5.png"));
}

TEST(Ensemble, ARerunKeepsCompletedMembersAndResumesAKilledOne) {
  test::useTestTerrainCache();
  const std::string dir = test::tempDir("ensemble_resume");
  const std::string scene = writeScene(dir, 30.0);
  const std::string ens = dir + "/ens";
  const std::string args = "ensemble " + scene + " --vary terrain.friction=0.25:0.35 --samples 3 --jobs 1 --out " + ens;
  // In its own session, so the ensemble and its running member can be killed together.
  FILE* p = popen(("setsid \"" TALUS_BINARY "\" " + args + " > " + dir + "/first.log 2>&1 & echo $!").c_str(), "r");
  ASSERT_TRUE(p);
  long pid = 0;
  ASSERT_EQ(fscanf(p, "%ld", &pid), 1);
  pclose(p);
  // Members run one at a time: once member_001 has a checkpoint, member_000 is done.
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(300);
  while (!fs::exists(ens + "/member_001/checkpoint.h5") && std::chrono::steady_clock::now() < deadline)
    std::this_thread::sleep_for(std::chrono::milliseconds(20));
  kill(-pid_t(pid), SIGKILL);
  for (int i = 0; i < 200 && kill(-pid_t(pid), 0) == 0; ++i) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  ASSERT_EQ(memberState(ens + "/member_000"), MemberState::Completed);
  ASSERT_EQ(memberState(ens + "/member_001"), MemberState::Partial) << "killed after its first checkpoint";
  const auto kept = fs::last_write_time(ens + "/member_000/summary.json");

  std::string out;
  ASSERT_EQ(test::runTalus(args, out), 0) << out;
  EXPECT_NE(out.find("1 of 3 members completed before, kept"), std::string::npos) << out;
  EXPECT_NE(out.find("resume from their checkpoints"), std::string::npos) << out;
  EXPECT_EQ(fs::last_write_time(ens + "/member_000/summary.json"), kept) << "a completed member is not run again";
  for (size_t m = 0; m < 3; ++m) EXPECT_EQ(memberState(ens + "/" + memberName(m)), MemberState::Completed);
  // The resumed member ends as an uninterrupted run of it would (Talus resumes bit-identically).
  std::string plan;
  {
    std::ifstream in(ens + "/plan.csv");
    std::getline(in, plan), std::getline(in, plan), std::getline(in, plan);
  }
  const std::string friction = plan.substr(plan.find(',') + 1);
  ASSERT_EQ(test::runTalus("run " + scene + " --quiet --threads 1 --out " + dir + "/fresh --set output.peak_files=true "
                           "--set terrain.friction=" + friction,
                           out),
            0)
      << out;
  const DemRaster a = analysis::readRaster(findPeakFile(ens + "/member_001", "pft"));
  const DemRaster b = analysis::readRaster(findPeakFile(dir + "/fresh", "pft"));
  ASSERT_EQ(a.height.size(), b.height.size());
  for (size_t c = 0; c < a.height.size(); ++c)
    if (std::isfinite(b.height[c])) {
      EXPECT_EQ(a.height[c], b.height[c]) << c;
    }
}

TEST(Ensemble, AMemberStoppedBySigintOrSigtermIsResumedNotRunAnew) {
  // Ctrl-C reaches every member: each writes a checkpoint and summary.json "interrupted".
  const std::string dir = test::tempDir("ensemble_states");
  auto member = [&](const std::string& name, const std::string& status, bool checkpoint) {
    const std::string d = dir + "/" + name;
    fs::create_directories(d);
    if (!status.empty()) std::ofstream(d + "/summary.json") << "{\n  \"status\": \"" << status << "\",\n}\n";
    if (checkpoint) std::ofstream(d + "/checkpoint.h5") << "x";
    return d;
  };
  EXPECT_EQ(memberState(member("interrupted", "interrupted", true)), MemberState::Partial);
  EXPECT_TRUE(memberInterrupted(dir + "/interrupted"));
  EXPECT_EQ(memberState(member("interrupted_no_checkpoint", "interrupted", false)), MemberState::Failed);
  EXPECT_EQ(memberState(member("write_failure", "failed: cannot write x: No space left on device", true)),
            MemberState::Failed);
  EXPECT_EQ(memberState(member("killed", "", true)), MemberState::Partial);
  EXPECT_FALSE(memberInterrupted(dir + "/killed"));
  EXPECT_EQ(memberState(member("done", "completed", true)), MemberState::Completed);
  EXPECT_EQ(memberState(member("missing", "", false)), MemberState::Missing);
}

TEST(Ensemble, SigtermStartsNoMoreMembersAndSaysHowToContinue) {
  // A batch system's `kill PID` reaches the ensemble only: its running member goes on to its end,
  // no other starts, and the ensemble exits 143 saying that a re-run continues.
  test::useTestTerrainCache();
  const std::string dir = test::tempDir("ensemble_sigterm"), ens = dir + "/ens";
  const std::string scene = writeScene(dir, 5.0);
  test::TalusProcess p({"ensemble", scene, "--vary", "terrain.friction=0.25:0.35", "--samples", "3", "--jobs", "1",
                        "--out", ens},
                       dir + "/log");
  ASSERT_TRUE(p.waitForFile(ens + "/member_000/checkpoint.h5"));
  p.signal(SIGTERM);
  const test::Exit e = p.wait();
  EXPECT_EQ(e.code, 143) << e.log;
  EXPECT_NE(e.log.find("interrupted by SIGTERM; 1 of 3 members completed; run the same command again"),
            std::string::npos) << e.log;
  EXPECT_EQ(memberState(ens + "/member_000"), MemberState::Completed);
  EXPECT_EQ(memberState(ens + "/member_001"), MemberState::Missing);
}
