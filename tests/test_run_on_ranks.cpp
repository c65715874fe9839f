// `mpirun -np N talus run`: the files are one process's, a run checkpointed at N ranks resumes
// at M, and a killed rank ends the job with the last checkpoint intact. Skipped without mpirun.
#include "samosat_slab.h"
#include "small_collapse.h"
#include "process_support.h"
#include "terrain_test_support.h"
#include "test_support.h"
#include "water_flume.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <iterator>
#include <regex>
#include <sstream>

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

/// A file's bytes, a VDB file's with its unique id (a UUID in its header, new in every file)
/// blanked.
std::string comparable(const fs::path& p) {
  std::string b = bytes(p);
  if (p.extension() != ".vdb") return b;
  static const std::regex uuid("[0-9a-f]{8}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{4}-[0-9a-f]{12}");
  std::smatch m;
  const std::string head = b.substr(0, 128);
  if (std::regex_search(head, m, uuid)) b.replace(size_t(m.position(0)), size_t(m.length(0)), size_t(m.length(0)), '-');
  return b;
}

/// What a run in `dir` says of the files it could not make: summary.json's "animation" (the
/// film's outcome) and ffmpeg's messages when it failed.
std::string why(const std::string& dir) {
  const std::string summary = bytes(fs::path(dir) / "summary.json");
  const size_t at = summary.find("\"animation\"");
  std::string said = at == std::string::npos ? "" : summary.substr(at, summary.find('\n', at) - at);
  return "\n(the run's summary: " + said + "; ffmpeg.log: " + bytes(fs::path(dir) / "animation" / "ffmpeg.log") + ")";
}

/// Every file of a against b's, except those that differ between two one-process runs too
/// (summary.json's wall times and report.html, which shows them), and the checkpoint: on ranks
/// it lists each rank's part (checkpoint_parts/), so the tests compare what it resumes to instead.
void expectSameFiles(const std::string& a, const std::string& b) {
  size_t compared = 0;
  for (const auto& e : fs::recursive_directory_iterator(a)) {
    if (!e.is_regular_file()) continue;
    const fs::path rel = fs::relative(e.path(), a);
    if (rel == "summary.json" || rel == "report.html" || rel == "checkpoint.h5") continue;
    ASSERT_TRUE(fs::exists(fs::path(b) / rel)) << rel << why(b);
    EXPECT_TRUE(comparable(e.path()) == comparable(fs::path(b) / rel)) << rel << " differs";
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

TEST(RunOnRanks, TheDefaultScenesFilesAtTwoAndFourRanksAreOneProcesss) {
  if (!haveMpirun()) GTEST_SKIP() << "mpirun not installed";
  const std::string dir = test::tempDir("ranks_default");
  std::string out;
  ASSERT_EQ(test::runTalus("run --quiet --set simulation.end_time=1.5 --threads 1 --out " + dir + "/one", out), 0) << out;
  for (int n : {2, 4}) {
    const std::string to = dir + "/" + std::to_string(n);
    ASSERT_EQ(test::shell(mpirun(n) + TALUS_BINARY " run --quiet --set simulation.end_time=1.5 --threads 1 --out " + to, out), 0) << out;
    expectSameFiles(dir + "/one", to);
    const std::string summary = bytes(to + "/summary.json");
    EXPECT_NE(summary.find("\"ranks\": " + std::to_string(n)), std::string::npos);
    EXPECT_NE(summary.find("\"communication_seconds\""), std::string::npos);
    // Each rank's memory: its particles, grid, terrain and peak resident set.
    size_t ranksWithMemory = 0;
    for (size_t at = summary.find("\"memory_bytes\": {\"particles\": "); at != std::string::npos;
         at = summary.find("\"memory_bytes\": {\"particles\": ", at + 1))
      ++ranksWithMemory;
    EXPECT_EQ(ranksWithMemory, size_t(n));
  }
  EXPECT_NE(bytes(dir + "/one/summary.json").find("\"memory_bytes\": {\"particles\": "), std::string::npos);
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

/// The files of dir/checkpoint_parts.
std::vector<std::string> partFiles(const std::string& dir) {
  std::vector<std::string> names;
  if (fs::exists(dir + "/checkpoint_parts"))
    for (const auto& e : fs::directory_iterator(dir + "/checkpoint_parts")) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

TEST(RunOnRanks, EachRankWritesItsPartOfACheckpointAndADamagedOrMissingPartIsRefusedByName) {
  if (!haveMpirun()) GTEST_SKIP() << "mpirun not installed";
  const std::string dir = test::tempDir("ranks_checkpoint_parts");
  const std::string scene = sceneFile(dir);
  // Frames every 0.02 s, so the resumed run's files below are enough to compare (12).
  const std::string set = " --set output.frame_interval=0.02 --quiet --threads 1";
  const std::string to5 = " --set simulation.end_time=0.05" + set, to6 = " --set simulation.end_time=0.06" + set;
  std::string out;
  ASSERT_EQ(test::shell(mpirun(2) + TALUS_BINARY " run " + scene + to5 + " --out " + dir + "/two", out), 0) << out;
  // The last checkpoint's two parts only: the four before it were removed once it was in place.
  const std::vector<std::string> parts = partFiles(dir + "/two");
  ASSERT_EQ(parts.size(), 2u) << "parts of older checkpoints are left";
  EXPECT_EQ(parts[0].substr(parts[0].size() - 9), "_rank0.h5");
  EXPECT_EQ(parts[1].substr(parts[1].size() - 9), "_rank1.h5");
  // Each rank's part holds its own particles, about half of them each, and together all of them:
  // rank 0 wrote the clock and the ledgers, not the particles. (Bytes: a part is its records.)
  const size_t a = fs::file_size(dir + "/two/checkpoint_parts/" + parts[0]), b = fs::file_size(dir + "/two/checkpoint_parts/" + parts[1]);
  EXPECT_GT(std::min(a, b), std::max(a, b) / 4) << a << " and " << b << " bytes";
  EXPECT_LT(fs::file_size(dir + "/two/checkpoint.h5"), std::min(a, b) / 4) << "the checkpoint itself holds particles";
  // One process resumes it (to 0.06 s) as it resumes its own checkpoint.
  ASSERT_EQ(test::runTalus("run " + scene + to6 + " --out " + dir + "/one", out), 0) << out;
  fs::copy(dir + "/two", dir + "/resumed", fs::copy_options::recursive);
  ASSERT_EQ(test::runTalus("run " + scene + to6 + " --resume " + dir + "/resumed", out), 0) << out;
  expectSameFiles(dir + "/one", dir + "/resumed");
  // A damaged part, then a missing one: refused, naming the part.
  fs::copy(dir + "/two", dir + "/damaged", fs::copy_options::recursive);
  const std::string part1 = dir + "/damaged/checkpoint_parts/" + parts[1];
  {
    std::fstream f(part1, std::ios::in | std::ios::out | std::ios::binary);
    f.seekp(long(b / 2));
    const char flipped = char(0x5a);
    f.write(&flipped, 1);
  }
  EXPECT_NE(test::runTalus("run " + scene + to6 + " --resume " + dir + "/damaged", out), 0);
  EXPECT_NE(out.find(parts[1] + ": a part of checkpoint"), std::string::npos) << out;
  EXPECT_NE(out.find("damaged (checksum mismatch)"), std::string::npos) << out;
  fs::remove(part1);
  EXPECT_NE(test::runTalus("run " + scene + to6 + " --resume " + dir + "/damaged", out), 0);
  EXPECT_NE(out.find(parts[1] + ": a part of checkpoint"), std::string::npos) << out;
  EXPECT_NE(out.find("missing"), std::string::npos) << out;
  // A run resumed in one process writes its checkpoints whole, and the parts go with the last one.
  EXPECT_TRUE(partFiles(dir + "/resumed").empty());
}

TEST(RunOnRanks, RanksThatDoNotShareTheOutputFolderGatherTheCheckpointToRankZero) {
  // Rank 1 runs in its own mount namespace with a tmpfs over the output folder: the same path,
  // another folder, as a node's own disk would be. Its part would be lost, so rank 0 writes the
  // checkpoint with every particle, as one process's, and says so.
  if (!haveMpirun()) GTEST_SKIP() << "mpirun not installed";
  std::string out;
  if (test::shell("unshare -m --propagation private true", out) != 0) GTEST_SKIP() << "no private mount namespace here (run as root): " << out;
  const std::string dir = test::tempDir("ranks_unshared");
  const std::string scene = sceneFile(dir), run = dir + "/run";
  fs::create_directories(run);
  const std::string talus = std::string(TALUS_BINARY " run ") + scene + " --set simulation.end_time=0.05 --set output.frame_interval=0.02 --quiet --threads 1 --out " + run;
  const std::string cmd = mpirun(2) + "sh -c 'if [ \"$OMPI_COMM_WORLD_RANK\" = 1 ]; then exec unshare -m --propagation private sh -c \"mount -t tmpfs none " +
                          run + " && exec " + talus + "\"; else exec " + talus + "; fi'";
  ASSERT_EQ(test::shell(cmd, out), 0) << out;
  EXPECT_NE(out.find("is not the same folder on every rank"), std::string::npos) << out;
  EXPECT_TRUE(partFiles(run).empty()) << "a rank wrote its part where the others cannot read it";
  // The checkpoint holds every particle: one process resumes it to a straight run's files.
  ASSERT_EQ(test::runTalus("run " + scene + " --set simulation.end_time=0.06 --set output.frame_interval=0.02 --quiet --threads 1 --out " + dir + "/one", out), 0) << out;
  ASSERT_EQ(test::runTalus("run " + scene + " --set simulation.end_time=0.06 --set output.frame_interval=0.02 --quiet --threads 1 --resume " + run, out), 0) << out;
  expectSameFiles(dir + "/one", run);
}

TEST(RunOnRanks, EachRankWritesItsPartOfEveryFrameAndRankZeroGathersNoFrame) {
  // Frames every 0.01 s in HDF5, PLY and VDB volumes: every rank writes its own particles' rows
  // into each particle file, and scatters them into the volume's nodes, which rank 0 adds up;
  // every file is one process's, and rank 0 gathers every particle twice (the start and the
  // end), not at the six frames after the first. VDB points need every particle: it does then.
  if (!haveMpirun()) GTEST_SKIP() << "mpirun not installed";
  const std::string dir = test::tempDir("ranks_frame_rows");
  const std::string scene = sceneFile(dir);
  const std::string set = " --set simulation.end_time=0.06 --set output.frame_interval=0.01 --set output.ply=true"
                          " --set output.checkpoint_interval=0 --quiet --threads 1 --set output.vdb_points=";
  auto gathers = [&](const std::string& run) {
    const std::string s = bytes(run + "/summary.json"), key = "\"rank0_gathered_every_particle\": ";
    const size_t at = s.find(key);
    return at == std::string::npos ? -1 : std::atoi(s.c_str() + at + key.size());
  };
  std::string out;
  ASSERT_EQ(test::runTalus("run " + scene + set + "false --out " + dir + "/one", out), 0) << out;
  for (int n : {2, 4}) {
    const std::string to = dir + "/" + std::to_string(n);
    ASSERT_EQ(test::shell(mpirun(n) + TALUS_BINARY " run " + scene + set + "false --out " + to, out), 0) << out;
    expectSameFiles(dir + "/one", to);
    EXPECT_TRUE(fs::exists(to + "/frames/particles_00006.ply") && fs::exists(to + "/frames/particles_00006.h5"));
    EXPECT_EQ(gathers(to), 2) << to;
  }
  EXPECT_TRUE(fs::exists(dir + "/2/frames/volume_00006.vdb"));
  ASSERT_EQ(test::shell(mpirun(2) + TALUS_BINARY " run " + scene + set + "true --out " + dir + "/points", out), 0) << out;
  EXPECT_EQ(gathers(dir + "/points"), 8);
  // Rank 1 under a file-size limit: its rows of the first frame it writes fail, and rank 0 names
  // the frame in one line; the frames before it stay whole and no temporary is left.
  const std::string limited = dir + "/limited";
  const std::string cmd = mpirun(2) + "sh -c 'if [ \"$OMPI_COMM_WORLD_RANK\" = 1 ]; then trap \"\" XFSZ; exec prlimit --fsize=4096 " TALUS_BINARY
                          " run " + scene + set + "false --out " + limited + "; else exec " TALUS_BINARY " run " + scene + set + "false --out " + limited + "; fi'";
  EXPECT_NE(test::shell(cmd, out), 0);
  EXPECT_NE(out.find("cannot write " + limited + "/frames/particles_00001.h5: File too large"), std::string::npos) << out;
  EXPECT_TRUE(bytes(limited + "/frames/particles_00000.h5") == bytes(dir + "/one/frames/particles_00000.h5"));
  EXPECT_FALSE(fs::exists(limited + "/frames/particles_00001.h5") || fs::exists(limited + "/frames/particles_00001.h5.tmp"));
}

TEST(RunOnRanks, AnErodibleFieldsRunAtTwoRanksWritesOneProcesssFiles) {
  // A snow slab sliding down a 30-degree DEM over a 0.2 m cover (0.4 cells: a field, issue 40):
  // the erosion-depth map, the entrained-mass series and the particles the pools made are one
  // process's at two ranks, and its checkpoint (written at two ranks) resumes at one. Then over
  // a 1 m cover (two cells: particles) listed in [output.maps] erodible, with AvaFrame's peak
  // files, for 1 s: its entrained mass in the series and the mass log, in parts on the ranks.
  if (!haveMpirun()) GTEST_SKIP() << "mpirun not installed";
  test::useTestTerrainCache();
  const std::string base = test::tempDir("ranks_erodible");
  constexpr double X0 = 2600000, Y0 = 1200000;
  writeDemGeoTiff(test::makeDem(80, 40, 0.5, X0, Y0, [](double x, double) { return 1000 - 0.57735 * (x - X0); }),
                  base + "/slope.tif");
  auto box = [&](double x0, double y0, double x1, double y1) {
    char b[160];
    std::snprintf(b, sizeof b, "[%.3f, %.3f, %.3f, %.3f]", X0 + x0, Y0 + y0, X0 + x1, Y0 + y1);
    return std::string(b);
  };
  struct Cover {
    std::string name, thickness, outputs, column, endTime;
    double coverEnd; ///< m along x
  };
  for (const Cover& c : {Cover{"field", "0.2", "maps = true\n", "entrained_mass_kg_field_cover", "2", 30},
                         Cover{"particles", "1.0", "peak_files = true\n[output.maps]\nerodible = [\"cover\"]\n",
                               "entrained_mass_kg_cover", "1", 20}}) {
    SCOPED_TRACE(c.name);
    const std::string dir = base + "/" + c.name, scene = dir + "/erodible.toml";
    fs::create_directories(dir);
    std::ofstream(scene) << "[simulation]\ndx = 0.5\nend_time = " + c.endTime + "\n[terrain]\ndem = \"" + base +
                                "/slope.tif\"\nboundary = \"friction\"\nfriction = 0.2\n[[materials]]\nname = \"snow\"\n"
                                "model = \"elastic\"\ndensity = 300\nyoungs_modulus = 1e6\n[[materials]]\nname = \"cover\"\n"
                                "model = \"elastic\"\ndensity = 100\nyoungs_modulus = 1e6\n[[bodies]]\nname = \"release\"\n"
                                "kind = \"layer\"\nmaterial = \"snow\"\nthickness = 2\nbounds = " + box(4, 6, 8, 14) +
                                "\n[[bodies]]\nname = \"cover\"\nkind = \"layer\"\nmaterial = \"cover\"\nthickness = " +
                                c.thickness + "\nthickness_direction = \"vertical\"\nerosion_energy = 200\nbounds = " +
                                box(8.5, 5, c.coverEnd, 15) + "\n[output]\nframe_interval = 0.5\ncheckpoint_interval = 0.4\n" + c.outputs;
    std::string out;
    ASSERT_EQ(test::runTalus("run " + scene + " --quiet --threads 1 --out " + dir + "/one", out), 0) << out;
    ASSERT_EQ(test::shell(mpirun(2) + TALUS_BINARY " run " + scene + " --quiet --threads 1 --out " + dir + "/two", out), 0) << out;
    expectSameFiles(dir + "/one", dir + "/two");
    const std::string summary = bytes(dir + "/one/summary.json");
    EXPECT_EQ(summary.find("\"erodible_fields\"") != std::string::npos, c.name == "field") << "the cover was made a field or not";
    // The slab took part of the cover (series.csv's last row: entrained kg).
    std::ifstream series(dir + "/one/series.csv");
    std::string header, line, last;
    std::getline(series, header);
    while (std::getline(series, line)) last = line;
    ASSERT_NE(header.find(c.column), std::string::npos) << header;
    const size_t column = size_t(std::count(header.begin(), header.begin() + long(header.find(c.column)), ','));
    std::stringstream cells(last);
    std::string cell;
    for (size_t k = 0; k <= column; ++k) std::getline(cells, cell, ',');
    EXPECT_GT(std::stod(cell), 100.0) << "too little entrained for the test to see the cover's ranks";
    EXPECT_TRUE(fs::exists(dir + "/two/maps/erosion_depth.tif"));
    // The two ranks' last checkpoint (t = 1.6 s; 0.8 s), resumed at one process, ends where one process did.
    ASSERT_EQ(test::runTalus("run " + scene + " --quiet --threads 1 --resume " + dir + "/two", out), 0) << out;
    expectSameFiles(dir + "/one", dir + "/two");
  }
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

TEST(RunOnRanks, ASignalToOneRankStopsEveryRankAtTheSameStepAndTheRunResumes) {
  // SIGTERM reaches rank 1 only (as from a node's own scheduler): the ranks agree on the flags in
  // the step's one reduction, so rank 0 stops at the same step, writes the checkpoint and the
  // summary, and one process resumes from it to a straight run's files.
  if (!haveMpirun()) GTEST_SKIP() << "mpirun not installed";
  const std::string dir = test::tempDir("ranks_signal");
  const std::string scene = sceneFile(dir), run = dir + "/run";
  const std::string set = " --set simulation.end_time=0.3 --set output.checkpoint_interval=0 --threads 1";
  // Within two minutes: ranks that disagreed would wait for each other for ever.
  const std::string cmd = "timeout 120 env " + mpirun(2) + "sh -c 'if [ \"$OMPI_COMM_WORLD_RANK\" = 1 ]; then (while [ ! -s " + run +
                          "/frames/particles_00001.h5 ]; do sleep 0.02; done; kill -TERM $$) & fi; exec " TALUS_BINARY
                          " run " + scene + set + " --out " + run + "'";
  std::string out;
  EXPECT_NE(test::shell(cmd, out), 0) << out;
  EXPECT_NE(out.find("interrupted by SIGTERM at step"), std::string::npos) << out;
  const std::string summary = bytes(run + "/summary.json");
  EXPECT_NE(summary.find("\"status\": \"interrupted\""), std::string::npos) << summary;
  EXPECT_NE(summary.find("\"interrupted_by\": \"SIGTERM\""), std::string::npos) << summary;
  ASSERT_TRUE(fs::exists(run + "/checkpoint.h5"));
  EXPECT_FALSE(fs::exists(run + "/particles.h5")) << "the run stopped before its end";
  ASSERT_EQ(test::runTalus("run " + scene + set + " --quiet --resume " + run, out), 0) << out;
  ASSERT_EQ(test::runTalus("run " + scene + set + " --quiet --out " + dir + "/straight", out), 0) << out;
  expectSameFiles(dir + "/straight", run);
}

namespace {

// A water dam break in a flume with two wave gauges and a section, and an elastic slab sliding
// down a tilted plane under samosAT (the thickness lines cross the ranks), with a probe and a
// path: each about a second at one process.
const std::string kOutputs = R"(
[output]
frame_interval = 0.2
checkpoint_interval = 0.1
series_interval = 0.01
)";
const std::string kWaterFlume = std::string(test::kWaterFlumeScene) + kOutputs + R"(
[[output.gauges]]
name = "near"
point = [1.0, 0.08]
[[output.gauges]]
name = "far"
point = [2.0, 0.08]
[[output.sections]]
name = "middle"
points = [[1.2, 0], [1.2, 0.16]]
)";
const std::string kSamosAtRun = with(test::kSamosAtSlab, "end_time = 1", "end_time = 0.6") + kOutputs + R"(
[[output.probes]]
name = "slab"
point = [1.0, 0.4, 0.2]
[[output.paths]]
name = "down"
points = [[0.2, 0.4], [3.0, 0.4]]
)";

} // namespace

TEST(RunOnRanks, WaterAndThicknessLawRunsAtTwoAndFourRanksWriteOneProcesssFilesAndResumeAtTwo) {
  // The issue-35 cases beside the default scene's: every file (series with gauges, sections,
  // probes and paths; frames; particles) one process's at 2 and 4 ranks, and the 4 ranks' last
  // checkpoint (t = 0.5 s) resumed at two ranks ends where one process did (rank 1 takes the
  // probe's place and the series' clock from rank 0, the sections' totals start again at zero). The flume once
  // more with its maps and plain series: then every per-step output (the run-up map too) steps
  // in parts and no particle is gathered between frames.
  if (!haveMpirun()) GTEST_SKIP() << "mpirun not installed";
  const std::string waterMaps =
      with(kWaterFlume.substr(0, kWaterFlume.find("[[output.gauges]]")), "series_interval = 0.01", "series_interval = 0.01\nmaps = true");
  for (const auto& [name, text] : {std::pair<std::string, std::string>{"water", kWaterFlume}, {"samosat", kSamosAtRun},
                                   {"water_maps", waterMaps}}) {
    SCOPED_TRACE(name);
    const std::string dir = test::tempDir("ranks_" + name), scene = dir + "/" + name + ".toml";
    std::ofstream(scene) << text;
    std::string out;
    const std::string args = " run " + scene + " --quiet --threads 1 --out " + dir;
    ASSERT_EQ(test::runTalus(args.substr(1) + "/one", out), 0) << out;
    for (int n : {2, 4}) {
      ASSERT_EQ(test::shell(mpirun(n) + TALUS_BINARY + args + "/" + std::to_string(n), out), 0) << out;
      expectSameFiles(dir + "/one", dir + "/" + std::to_string(n));
    }
    ASSERT_EQ(test::shell(mpirun(2) + TALUS_BINARY + args.substr(0, args.find(" --out")) + " --resume " + dir + "/4", out), 0) << out;
    expectSameFiles(dir + "/one", dir + "/4");
  }
}
