// The checkpoint file refuses, with one line naming it and the reason, everything that is not a
// whole checkpoint of this scene written by this Talus: missing, empty, truncated, damaged data
// or header, not a checkpoint, format 1, another format, another version, another scene.
#include "io/common/h5_file.h"
#include "io/common/input_error.h"
#include "io/run/checkpoint.h"
#include "process_support.h"
#include "test_support.h"

#include <gtest/gtest.h>
#include <unistd.h>
#include <zlib.h>

using namespace talus;

namespace {

const char* kScene = R"(
[simulation]
dx = 0.1
end_time = 0.2
[domain]
min = [0, 0, 0]
max = [1, 1, 1]
[[materials]]
name = "rock"
preset = "rock"
[[bodies]]
material = "rock"
shape = "sphere"
center = [0.5, 0.5, 0.5]
radius = 0.2
[output]
series = false
)";

const CheckpointIdentity kId{"00000000000000aa"};

struct Fixture {
  std::string dir, good;
  std::string bytes; ///< the good checkpoint's bytes
};

const Fixture& fixture() {
  static const Fixture f = [] {
    Fixture x;
    // Per process: ctest runs this file's tests in parallel processes, each building the fixture.
    x.dir = test::tempDir("checkpoint_file_" + std::to_string(::getpid()));
    x.good = x.dir + "/good.h5";
    auto sim = test::makeSimulation(kScene);
    for (int i = 0; i < 5; ++i) sim->step();
    writeCheckpoint(x.good, *sim, kId);
    x.bytes = test::slurp(x.good);
    return x;
  }();
  return f;
}

std::string write(const std::string& name, const std::string& bytes) {
  const std::string p = fixture().dir + "/" + name;
  std::ofstream(p, std::ios::binary) << bytes;
  return p;
}

/// The header with `from` replaced by `to` (same length) and its own checksum made right again,
/// as another Talus would have written it.
std::string resealedHeader(std::string bytes, const std::string& from, const std::string& to) {
  bytes.replace(bytes.find(from), from.size(), to);
  const size_t line = bytes.find("header_crc32 ");
  char hex[16];
  std::snprintf(hex, sizeof hex, "%08lx", crc32(0, reinterpret_cast<const Bytef*>(bytes.data()), uInt(line)));
  bytes.replace(line + 13, 8, hex);
  return bytes;
}

/// readCheckpoint refuses `path` with a one-line message naming it and containing `why`.
void expectRefused(const std::string& path, const std::string& why, const CheckpointIdentity& id = kId) {
  auto sim = test::makeSimulation(kScene);
  try {
    readCheckpoint(path, *sim, id);
    FAIL() << path << " was accepted (expected: " << why << ")";
  } catch (const InputError& e) {
    const std::string m = e.what();
    EXPECT_EQ(m.rfind(path + ": ", 0), 0u) << m;
    EXPECT_NE(m.find(why), std::string::npos) << m;
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
  }
}

} // namespace

TEST(CheckpointFile, AWholeCheckpointOfThisSceneIsAccepted) {
  auto sim = test::makeSimulation(kScene);
  readCheckpoint(fixture().good, *sim, kId);
  EXPECT_EQ(sim->steps(), 5u);
  const CheckpointHeader h = inspectCheckpoint(fixture().good);
  EXPECT_EQ(h.format, kCheckpointFormat);
  EXPECT_EQ(h.talusVersion, talusVersion());
  EXPECT_EQ(h.sceneHash, kId.sceneHash);
}

TEST(CheckpointFile, MissingEmptyAndNonFilesAreRefused) {
  expectRefused(fixture().dir + "/none.h5", "no checkpoint to resume from");
  expectRefused(write("empty.h5", ""), "empty");
  std::filesystem::create_directories(fixture().dir + "/folder.h5");
  expectRefused(fixture().dir + "/folder.h5", "not a regular file");
  expectRefused(write("text.h5", "time,ke\n0,1\n"), "not a Talus checkpoint");
}

TEST(CheckpointFile, TruncationAnywhereIsRefused) {
  const std::string& b = fixture().bytes;
  expectRefused(write("cut_header.h5", b.substr(0, 100)), "truncated (100 bytes)");
  expectRefused(write("cut_after_header.h5", b.substr(0, 512)), "truncated");
  expectRefused(write("cut_half.h5", b.substr(0, b.size() / 2)), "truncated");
  expectRefused(write("cut_last_byte.h5", b.substr(0, b.size() - 1)), "truncated");
  expectRefused(write("extended.h5", b + "x"), "extended");
}

TEST(CheckpointFile, AFlippedBitInTheDataOrTheHeaderIsRefused) {
  std::string b = fixture().bytes;
  for (size_t at : {size_t(600), b.size() / 2, b.size() - 1}) {
    std::string d = b;
    d[at] ^= 0x10;
    expectRefused(write("flip_" + std::to_string(at) + ".h5", d), "damaged (checksum mismatch)");
  }
  std::string h = b;
  h[h.find("bytes ") + 6] ^= 0x01; // the recorded length
  expectRefused(write("flip_header.h5", h), "damaged header");
}

TEST(CheckpointFile, Format1OtherFormatsAndOtherVersionsAreRefusedWithTheReason) {
  { // Talus before checksums wrote a plain HDF5 file
    h5::Handle f = h5::createFile(fixture().dir + "/format1.h5");
    h5::writeAttribute(f, "time", 0.1);
    h5::closeFile(f);
  }
  expectRefused(fixture().dir + "/format1.h5", "format 1");
  expectRefused(write("format4.h5", resealedHeader(fixture().bytes, "format 3", "format 4")),
                "checkpoint format 4; this Talus reads formats 2 to 3");
  // Format 2 is format 3 without the parts of a checkpoint written on ranks: still read.
  EXPECT_EQ(inspectCheckpoint(write("format2.h5", resealedHeader(fixture().bytes, "format 3", "format 2"))).format, 2);
  const std::string v = std::string("talus ") + talusVersion();
  std::string other = v;
  other.back() = other.back() == '9' ? '8' : '9';
  expectRefused(write("version.h5", resealedHeader(fixture().bytes, v, other)),
                "written by Talus " + other.substr(6) + "; this is Talus " + talusVersion());
}

TEST(CheckpointFile, ACheckpointOfAnotherSceneIsRefused) {
  expectRefused(fixture().good, "written for another scene (scene hash 00000000000000aa, this scene 00000000000000bb)",
                CheckpointIdentity{"00000000000000bb"});
}

TEST(CheckpointFile, ResumingWithAnotherSceneOrOverrideIsRefusedWithExitStatus2) {
  const std::string dir = test::tempDir("checkpoint_other_scene");
  std::ofstream(dir + "/scene.toml") << kScene << "checkpoint_interval = 0.05\n";
  const std::vector<std::string> run{"run", dir + "/scene.toml", "--out", dir + "/out", "--quiet"};
  ASSERT_EQ(test::runTalusProcess(run, dir + "/log").code, 0);
  const test::Exit e = test::runTalusProcess(
      {"run", dir + "/scene.toml", "--resume", dir + "/out", "--quiet", "--set", "simulation.cfl=0.3"}, dir + "/log2");
  EXPECT_EQ(e.code, 2) << e.log;
  ASSERT_EQ(e.lines().size(), 1u) << e.log;
  EXPECT_NE(e.log.find(dir + "/out/checkpoint.h5: written for another scene"), std::string::npos) << e.log;
  // The same scene and overrides resume.
  EXPECT_EQ(test::runTalusProcess({"run", dir + "/scene.toml", "--resume", dir + "/out", "--quiet"}, dir + "/log3").code, 0);
}
