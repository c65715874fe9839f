// Checkpoints: a run resumed from a checkpoint ends bit-identical to an uninterrupted one.
#include "io/run/checkpoint.h"
#include "test_support.h"

#include <cstring>
#include <fstream>
#include <gtest/gtest.h>

using namespace talus;

namespace {
// Every model at once: elastic, Drucker-Prager, Cam Clay and water, so all state is covered.
const char* kMixed = R"(
[simulation]
dx = 0.1
end_time = 1
[domain]
min = [0, 0, 0]
max = [3, 1, 2]
walls = "slip"
[[materials]]
name = "rubber"
model = "elastic"
density = 1000
youngs_modulus = 1e6
[[materials]]
name = "rock"
preset = "rock"
[[materials]]
name = "snow"
preset = "snow"
[[materials]]
name = "water"
model = "water"
density = 1000
sound_speed = 40
[[bodies]]
material = "water"
shape = "box"
min = [0, 0, 0]
max = [1.0, 1.0, 0.6]
[[bodies]]
material = "snow"
shape = "box"
min = [1.5, 0, 0]
max = [3.0, 1.0, 0.4]
[[bodies]]
material = "rock"
shape = "sphere"
center = [2.2, 0.5, 1.0]
radius = 0.25
velocity = [0, 0, -8]
[[bodies]]
material = "rubber"
shape = "box"
min = [0.3, 0.3, 1.0]
max = [0.6, 0.6, 1.3]
)";

// The scene hash is checked separately (CheckpointFile tests); these use one fixed identity.
const CheckpointIdentity kId{"0123456789abcdef"};

std::vector<char> snapshot(const Simulation& sim) {
  std::vector<char> bytes;
  auto append = [&](const auto& v) {
    const char* p = reinterpret_cast<const char*>(v.data());
    bytes.insert(bytes.end(), p, p + v.size() * sizeof(v[0]));
  };
  for (const auto* g : sim.groups()) {
    append(g->particles.x);
    append(g->particles.v);
    append(g->particles.C);
    append(g->particles.tau);
  }
  const double t = sim.time();
  bytes.insert(bytes.end(), reinterpret_cast<const char*>(&t), reinterpret_cast<const char*>(&t) + sizeof t);
  return bytes;
}
} // namespace

TEST(Checkpoint, ResumedRunEndsBitIdenticalToUninterrupted) {
  const std::string dir = test::tempDir("checkpoint");
  auto straight = test::makeSimulation(kMixed);
  for (int i = 0; i < 150; ++i) straight->step();

  auto first = test::makeSimulation(kMixed);
  for (int i = 0; i < 60; ++i) first->step();
  writeCheckpoint(checkpointPath(dir), *first, kId, [](StateArchive& a) { a.putValue("next_frame", int32_t(7)); });
  first.reset(); // the "killed" run

  auto resumed = test::makeSimulation(kMixed);
  int frame = 0;
  readCheckpoint(checkpointPath(dir), *resumed, kId, [&](const StateArchive& a) { frame = a.getValue<int32_t>("next_frame"); });
  EXPECT_EQ(frame, 7);
  EXPECT_EQ(resumed->steps(), 60u);
  for (int i = 0; i < 90; ++i) resumed->step();
  EXPECT_EQ(resumed->steps(), straight->steps());
  const auto a = snapshot(*straight), b = snapshot(*resumed);
  ASSERT_EQ(a.size(), b.size());
  EXPECT_EQ(std::memcmp(a.data(), b.data(), a.size()), 0);
  EXPECT_EQ(resumed->totalMassRemoved(), straight->totalMassRemoved());
}

TEST(Checkpoint, MismatchedSceneAndMissingFileAreRefusedWithTheFileName) {
  const std::string dir = test::tempDir("checkpoint_mismatch");
  auto sim = test::makeSimulation(kMixed);
  sim->step();
  writeCheckpoint(checkpointPath(dir), *sim, kId);
  std::string other = kMixed;
  other.replace(other.find("name = \"snow\""), 13, "name = \"firn\"");
  other.replace(other.find("material = \"snow\""), 17, "material = \"firn\"");
  auto wrong = test::makeSimulation(other);
  try {
    readCheckpoint(checkpointPath(dir), *wrong, kId);
    FAIL() << "a checkpoint of another scene was accepted";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("checkpoint.h5"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("firn"), std::string::npos) << e.what();
  }
  EXPECT_THROW(readCheckpoint(dir + "/nothing/checkpoint.h5", *wrong, kId), InputError);
}

TEST(Checkpoint, AnInterruptedWriteLeavesThePreviousCheckpointReadable) {
  const std::string dir = test::tempDir("checkpoint_atomic");
  auto sim = test::makeSimulation(kMixed);
  sim->step();
  writeCheckpoint(checkpointPath(dir), *sim, kId);
  // A writer killed mid-way leaves only a truncated temporary file behind.
  { std::ofstream(checkpointPath(dir) + ".tmp") << "truncated"; }
  auto again = test::makeSimulation(kMixed);
  readCheckpoint(checkpointPath(dir), *again, kId);
  EXPECT_EQ(again->steps(), 1u);
}
