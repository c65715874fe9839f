// Rank 0's view of the run (io/run/run.cpp, Simulation::gatherInto): the particles of every rank
// come to it one rank at a time, into arrays sized for all of them, and it holds them only while
// files are written from it; for those files the other ranks on its machine lend it their cores.
// Run under mpirun with the other MPI tests (tests/CMakeLists.txt).
#include "engine/simulation.h"
#include "io/run/run.h"
#include "io/run/run_ranks.h"
#include "io/scene/scene.h"
#include "small_collapse.h"
#include "world.h"

#include <algorithm>
#include <cstring>
#include <filesystem>
#include <gtest/gtest.h>
#include <sched.h>
#include <stdexcept>
#include <unistd.h>

using namespace talus;
using talus::test::world;

TEST(RankZero, AGatherLargerThanOneMessageArrivesOneRankAtATimeInRankOrder) {
  // Rank 0's view of a large run passes MPI's 2 GiB int counts; here the pieces are 1000 bytes.
  const size_t keep = world->maxMessageBytes;
  world->maxMessageBytes = 1000;
  std::vector<char> mine(size_t(10007 + 3 * world->rank()));
  for (size_t i = 0; i < mine.size(); ++i) mine[i] = char((i * 7 + size_t(world->rank())) % 251);
  std::vector<size_t> counts;
  int next = 0;
  world->gatherEach(
      mine, [&](const std::vector<size_t>& c) { counts = c; },
      [&](int r, std::string_view part) {
        ASSERT_EQ(r, next++) << "the ranks' parts come in rank order";
        ASSERT_EQ(counts.size(), size_t(world->size())) << "the counts come first";
        ASSERT_EQ(part.size(), counts[size_t(r)]);
        ASSERT_EQ(part.size(), size_t(10007 + 3 * r));
        for (size_t i = 0; i < part.size(); ++i) ASSERT_EQ(part[i], char((i * 7 + size_t(r)) % 251)) << r << " " << i;
      });
  // gather() is the same exchange, its parts put end to end.
  const std::vector<char> all = world->gather(mine, counts);
  world->maxMessageBytes = keep;
  if (world->rank() != 0) {
    EXPECT_EQ(next, 0) << "only rank 0 takes parts";
    EXPECT_TRUE(all.empty());
    return;
  }
  EXPECT_EQ(next, world->size());
  size_t at = 0;
  for (int r = 0; r < world->size(); ++r) {
    ASSERT_EQ(counts[size_t(r)], size_t(10007 + 3 * r));
    for (size_t i = 0; i < counts[size_t(r)]; ++i) ASSERT_EQ(all[at + i], char((i * 7 + size_t(r)) % 251)) << r << " " << i;
    at += counts[size_t(r)];
  }
  EXPECT_EQ(at, all.size());
}

// The view is filled for frames (every 0.04 s), checkpoints (every 0.03 s) and the end, and
// empty between them: rank 0 then holds its own share of the particles, not the whole run too.
TEST(RankZero, HoldsEveryParticleOnlyWhileItWrites) {
  std::string scene = test::kSmallCollapse;
  scene.replace(scene.find("end_time = 1"), 12, "end_time = 0.1");
  scene += R"(
[output]
frame_interval = 0.04
checkpoint_interval = 0.03
)";
  const auto dir = std::filesystem::temp_directory_path() / ("talus_test_rank_zero_view_" + std::to_string(world->size()));
  if (world->rank() == 0) std::filesystem::remove_all(dir); // only rank 0 writes
  auto load = [&] { return loadSceneString(scene, "collapse.toml", {}); };
  RunOptions opt;
  opt.outDir = dir.string();
  opt.threads = 1;
  opt.progress = false;
  opt.ranks = world;
  talus::Run run(load(), opt);
  const bool root = world->rank() == 0;
  EXPECT_EQ(run.viewCapacity(), 0u) << "after the start's frame the view is emptied";
  int steps = 0;
  while (run.step())
    if (++steps, root && run.viewCapacity() != 0) {
      ADD_FAILURE() << "the view holds " << run.viewCapacity() << " particles between writes, after step " << steps;
      break; // not return: every rank must step to the end together
    }
  ASSERT_EQ(run.result().status, RunStatus::Completed);
  const size_t all = run.simulation().globalParticleCount();
  if (!root) return;
  // The end's files were written from a view of exactly every particle: sized once for all of
  // them, not grown by doubling as each rank's part came in.
  EXPECT_EQ(run.viewCapacity(), all);
  EXPECT_GT(all, 12000u);
  const auto& files = run.result().files;
  EXPECT_NE(std::find(files.begin(), files.end(), "frames/particles_00002.h5"), files.end()) << "frames were written";
  EXPECT_GE(run.result().checkpointTime, 0.06) << "checkpoints were written";
}

namespace {
/// This rank's host name and CPU set, as the loan reads them.
struct Place {
  char host[64] = {};
  cpu_set_t cpus;
};
Place here() {
  Place p;
  gethostname(p.host, sizeof p.host - 1);
  sched_getaffinity(0, sizeof p.cpus, &p.cpus);
  return p;
}
} // namespace

TEST(RankZero, BorrowsTheCpusOfTheRanksOnItsMachineForTheEndsFiles) {
  // mpirun binds each of two ranks to its own core: rank 0 draws the film and maps at the end
  // with both, while the other sleeps (at four ranks on two cores nothing is bound and the sets
  // are already whole).
  const Place mine = here();
  std::vector<char> bytes(sizeof mine);
  std::memcpy(bytes.data(), &mine, sizeof mine);
  std::vector<size_t> counts;
  const std::vector<char> all = world->gather(bytes, counts);
  cpu_set_t wide = mine.cpus;
  int ranksHere = 0;
  for (size_t at = 0; at + sizeof mine <= all.size(); at += sizeof mine) {
    Place other;
    std::memcpy(&other, all.data() + at, sizeof other);
    if (std::strncmp(other.host, mine.host, sizeof mine.host) != 0) continue;
    CPU_OR(&wide, &wide, &other.cpus);
    ++ranksHere;
  }
  RunRanks ranks(world);
  const bool root = world->rank() == 0;
  {
    const CoreLoan loan(ranks, 1);
    const Place during = here();
    if (root) {
      EXPECT_TRUE(CPU_EQUAL(&during.cpus, &wide)) << "rank 0 runs on every lent CPU";
      EXPECT_EQ(loan.cores(), std::min(CPU_COUNT(&wide), ranksHere)) << "one thread per lending rank at most";
    } else {
      EXPECT_TRUE(CPU_EQUAL(&during.cpus, &mine.cpus)) << "a lender keeps its own set";
      EXPECT_EQ(loan.cores(), 0);
    }
    EXPECT_EQ(world->maxOfIdle(world->rank()), world->size() - 1) << "the sleeping wait is a reduction";
  }
  const Place after = here();
  EXPECT_TRUE(CPU_EQUAL(&after.cpus, &mine.cpus)) << "the loan ends with rank 0 on its own set";
  // A failure on rank 0 during the loan reaches every rank, as onRoot's does.
  bool peerFailed = false, thrown = false;
  try {
    ranks.onRootWithNodeCores(1, [](int) { throw std::runtime_error("disk full"); });
  } catch (const PeerFailed&) {
    peerFailed = true;
  } catch (const std::runtime_error&) {
    thrown = true;
  }
  EXPECT_EQ(thrown, root);
  EXPECT_EQ(peerFailed, !root);
}

TEST(RankZero, StartsFromTheRanksSeededPartsInOneProcesssOrderWindowByWindow) {
  // Each rank seeds its part; rank 0's view gets them all in the order one process seeds them,
  // here in windows of 150 particles (a message at most), without loading the scene again.
  SeedSlice part;
  part.part = world->rank(), part.parts = world->size();
  SceneSetup mine = loadSceneString(test::kSmallCollapse, "collapse.toml", {}, part);
  const std::vector<std::vector<uint64_t>> index = mine.seedSlice.index;
  Simulation sim(mine.settings, std::move(mine.groups));
  const bool root = world->rank() == 0;
  std::unique_ptr<Simulation> view = root ? sim.emptyView() : nullptr;
  const size_t keep = world->maxMessageBytes;
  world->maxMessageBytes = 150 * (8 + ParticleSet::bytesPerParticle() + sim.groups()[0]->stateBytesPerParticle());
  sim.gatherSeededInto(*world, view.get(), &index);
  world->maxMessageBytes = keep;
  if (!root) return;
  SceneSetup whole = loadSceneString(test::kSmallCollapse, "collapse.toml", {});
  const Simulation one(whole.settings, std::move(whole.groups));
  const MaterialGroup& a = *one.groups()[0];
  const MaterialGroup& b = *view->groups()[0];
  ASSERT_EQ(b.size(), a.size());
  EXPECT_GT(a.size(), 12000u);
  EXPECT_EQ(b.particles.x.capacity(), a.size()) << "sized once for all of them";
  std::vector<uint32_t> all(a.size());
  for (uint32_t i = 0; i < all.size(); ++i) all[i] = i;
  std::vector<char> ra, rb;
  packParticles(a, all, ra);
  packParticles(b, all, rb);
  EXPECT_TRUE(ra == rb) << "every particle's record, bit for bit, in one process's order";
  EXPECT_EQ(view->initialMass(), one.initialMass());
  EXPECT_EQ(view->maxSpeed(), one.maxSpeed());
  EXPECT_EQ(std::string(b.modelName()), a.modelName());
  EXPECT_EQ(b.waveSpeed(), a.waveSpeed()) << "the same material";
}
