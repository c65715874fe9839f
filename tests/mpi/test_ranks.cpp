// Rank-count invariance of the distributed step (engine/domain_decomposition.h,
// engine/halo_exchange.h). Run under mpirun at 2 and 4 ranks (tests/CMakeLists.txt): every rank
// runs the scene distributed, rank 0 also runs it as one process, and the ranks' particles,
// concatenated in rank order, must equal the one process's arrays bit for bit.
#include "engine/bspline.h"
#include "engine/mpi_communicator.h"
#include "engine/simulation.h"
#include "io/scene/scene.h"
#include "samosat_slab.h"
#include "small_collapse.h"
#include "world.h"

#include <cstring>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

using namespace talus;

std::shared_ptr<Communicator> talus::test::world;

namespace {

using talus::test::world;

/// Every particle array and every state variable the model reports, in particle order. (The
/// state records themselves may hold padding bytes, e.g. Cam Clay's flag: not compared.)
std::vector<std::vector<char>> arrays(const MaterialGroup* g) {
  auto bytes = [](const auto& v) {
    const char* p = reinterpret_cast<const char*>(v.data());
    return std::vector<char>(p, p + v.size() * sizeof(v[0]));
  };
  const auto& P = g->particles;
  std::vector<std::vector<char>> out{bytes(P.x), bytes(P.v), bytes(P.C), bytes(P.tau), bytes(P.mass)};
  std::vector<float> values;
  for (const std::string& name : g->scalarNames()) {
    g->scalar(name, values);
    out.push_back(bytes(values));
  }
  return out;
}

std::vector<char> snapshot(const Simulation& sim) {
  std::vector<char> out;
  for (const MaterialGroup* g : sim.groups())
    for (const auto& a : arrays(g)) out.insert(out.end(), a.begin(), a.end());
  return out;
}

/// The distributed particles gathered to every rank in snapshot()'s layout: each array is the
/// ranks' parts in rank order.
std::vector<char> gathered(const Simulation& sim) {
  std::vector<char> out;
  for (const MaterialGroup* g : sim.groups())
    for (const auto& a : arrays(g)) {
      std::vector<size_t> counts;
      const auto all = world->allGather(a, counts);
      out.insert(out.end(), all.begin(), all.end());
    }
  return out;
}

struct RankRun {
  std::unique_ptr<Simulation> sim;
  std::vector<char> particles; ///< gathered
};

RankRun runDistributed(const std::string& toml, const std::vector<std::string>& overrides, int steps,
                   double imbalance = 0.1) {
  SceneSetup s = loadSceneString(toml, "test.toml", overrides);
  RankRun r;
  r.sim = std::make_unique<Simulation>(s.settings, std::move(s.groups));
  r.sim->distribute(world, imbalance);
  for (int i = 0; i < steps; ++i) r.sim->step();
  r.particles = gathered(*r.sim);
  return r;
}

std::vector<char> runAlone(const std::string& toml, const std::vector<std::string>& overrides, int steps) {
  SceneSetup s = loadSceneString(toml, "test.toml", overrides);
  Simulation sim(s.settings, std::move(s.groups));
  for (int i = 0; i < steps; ++i) sim.step();
  return snapshot(sim);
}

/// Bit-identical particles at this rank count and in one process (checked on rank 0).
void expectInvariant(const RankRun& r, const std::string& toml, const std::vector<std::string>& overrides, int steps) {
  if (world->rank() != 0) return;
  const std::vector<char> alone = runAlone(toml, overrides, steps);
  ASSERT_EQ(alone.size(), r.particles.size());
  EXPECT_EQ(std::memcmp(alone.data(), r.particles.data(), alone.size()), 0)
      << "the particles at " << world->size() << " ranks differ from one process's";
}

// An elastic block sliding along +x on a Coulomb floor, through the ranks' ranges.
const char* kSlidingBlock = R"(
[simulation]
dx = 0.05
particles_per_cell = 8
end_time = 1
[domain]
min = [0, 0, 0]
max = [3.2, 0.8, 0.8]
walls = "slip"
[terrain]
plane = { point = [0, 0, 0.1], normal = [0, 0, 1] }
boundary = { law = "coulomb", friction = 0.1 }
[[materials]]
name = "jelly"
model = "elastic"
density = 1000
youngs_modulus = 2e5
poisson_ratio = 0.3
[[bodies]]
material = "jelly"
shape = "box"
center = [0.5, 0.4, 0.3]
size = [0.6, 0.4, 0.4]
velocity = [6, 0, 0]
)";

const std::string kCollapse = test::kSmallCollapse;

// Water at rest in two stacked bodies (hydrostatic start: each column's top is seen over both)
// beside a granular heap: two groups, two bodies in one of them.
const char* kTwoGroups = R"(
[simulation]
dx = 0.05
particles_per_cell = 8
end_time = 1
[domain]
min = [0, 0, 0]
max = [2.4, 0.4, 0.8]
walls = "slip"
[[materials]]
name = "water"
model = "water"
density = 1000
sound_speed = 20
[[materials]]
name = "sand"
model = "drucker_prager"
density = 1600
youngs_modulus = 1e6
poisson_ratio = 0.3
friction_angle = 30
[[bodies]]
material = "water"
shape = "box"
min = [0, 0, 0]
max = [0.9, 0.4, 0.2]
[[bodies]]
material = "sand"
shape = "box"
min = [1.4, 0, 0]
max = [2.2, 0.4, 0.3]
[[bodies]]
material = "water"
shape = "box"
min = [0, 0, 0.2]
max = [0.9, 0.4, 0.45]
)";

/// Each rank seeds its part of the scene (SeedSlice), then distribute() puts the particles in
/// one process's order on their owners.
RankRun runSeededOnRanks(const std::string& toml, const std::vector<std::string>& overrides, int steps) {
  SeedSlice part;
  part.part = world->rank(), part.parts = world->size();
  SceneSetup s = loadSceneString(toml, "test.toml", overrides, part);
  size_t held = 0;
  for (const auto& g : s.groups) held += g->size();
  // Every rank seeds only its rows: no rank holds them all (at 2 ranks and more).
  EXPECT_LT(world->maxOf(double(held)), double(s.seededParticles()));
  EXPECT_EQ(world->sumOf(held), s.seededParticles()) << "every particle is seeded on exactly one rank";
  RankRun r;
  r.sim = std::make_unique<Simulation>(s.settings, std::move(s.groups));
  r.sim->distribute(world, 0.1, &s.seedSlice.index);
  for (int i = 0; i < steps; ++i) r.sim->step();
  r.particles = gathered(*r.sim);
  return r;
}

} // namespace

TEST(Ranks, EachRankSeedingItsPartGivesOneProcesssParticles) {
  for (const std::string& toml : {std::string(kTwoGroups), kCollapse}) {
    RankRun r = runSeededOnRanks(toml, {}, 60);
    expectInvariant(r, toml, {}, 60);
  }
  // Stratified random samples (not a lattice), which may fall anywhere in their cells.
  const std::vector<std::string> random{"simulation.particles_per_cell=5"};
  RankRun w = runSeededOnRanks(kTwoGroups, random, 60);
  expectInvariant(w, kTwoGroups, random, 60);
  RankRun r = runSeededOnRanks(defaultSceneText(), {"simulation.end_time=0.3"}, 40);
  expectInvariant(r, defaultSceneText(), {"simulation.end_time=0.3"}, 40);
}

TEST(Ranks, OneReductionTakesTheMinimaOfOnePartAndTheSumsOfTheOther) {
  // Communicator::minimumAndSum, the step's one reduction after G2P: rank r gives minima
  // (r + 0.5, -r, 7) and sums (1, r, 1e15 + r: exact below 2^53 in any order); any mixing of the
  // parts or a lost rank shows.
  const int n = world->size(), r = world->rank();
  const uint64_t calls = world->collectives;
  double mins[3] = {r + 0.5, -double(r), 7.0};
  double sums[3] = {1.0, double(r), 1e15 + r};
  world->minimumAndSum(mins, 3, sums, 3);
  EXPECT_EQ(world->collectives, calls + 1) << "one collective";
  EXPECT_EQ(mins[0], 0.5);
  EXPECT_EQ(mins[1], -double(n - 1));
  EXPECT_EQ(mins[2], 7.0);
  EXPECT_EQ(sums[0], double(n));
  EXPECT_EQ(sums[1], double(n * (n - 1) / 2));
  EXPECT_EQ(sums[2], double(n) * 1e15 + double(n * (n - 1) / 2));
}

TEST(Ranks, AnElasticBlockSlidingThroughThreeRanksRangesIsBitIdentical) {
  // No rebalancing: the ranges stay where the block started, so it slides out of rank 0's
  // range through the others' (4 ranks: three boundaries crossed).
  RankRun r = runDistributed(kSlidingBlock, {}, 150, 1e9);
  const uint64_t moved = world->sumOf(r.sim->particleCount() ? 1 : 0);
  EXPECT_GE(moved, 1u);
  // Every particle lies in a block of its own rank.
  const DomainDecomposition& dd = *r.sim->ranks();
  for (const MaterialGroup* g : r.sim->groups())
    for (const Vec3& x : g->particles.x)
      ASSERT_EQ(dd.owner(owningBlock(x, Real(1) / Real(0.05))), world->rank());
  // It did cross the ranges: at the start the last rank held no more than its quarter; now the
  // block (moved ~0.9 m, more than its length) sits beyond the first rank's range.
  EXPECT_EQ(world->sumOf(world->rank() == 0 ? r.sim->particleCount() : 0), 0u) << "the block never left rank 0";
  expectInvariant(r, kSlidingBlock, {}, 150);
}

TEST(Ranks, AGranularCollapseIsBitIdentical) {
  RankRun r = runDistributed(kCollapse, {}, 200);
  EXPECT_GT(world->sumOf(r.sim->ranks()->rebalances), 0u) << "the collapse spreads: ranks should rebalance";
  expectInvariant(r, kCollapse, {}, 200);
}

TEST(Ranks, AnAflipCollapseIsBitIdentical) {
  // AFLIP's momentum channels are summed across ranks with the other extra channels.
  const std::vector<std::string> flip{"simulation.flip=0.9"};
  RankRun r = runDistributed(kCollapse, flip, 200);
  expectInvariant(r, kCollapse, flip, 200);
}

TEST(Ranks, UnequalSharesMoveTheRangesNotTheResults) {
  // talus run gives rank 0 a smaller share when the outputs it writes cost time
  // (io/run/run_ranks.h); here it is given none halfway through.
  SceneSetup s = loadSceneString(kCollapse, "test.toml", {});
  RankRun r;
  r.sim = std::make_unique<Simulation>(s.settings, std::move(s.groups));
  r.sim->distribute(world, 0.1);
  for (int i = 0; i < 200; ++i) {
    if (i == 100) {
      std::vector<double> shares(size_t(world->size()), 1.0 / (world->size() - 1));
      shares[0] = 0;
      r.sim->setRankShares(shares);
    }
    r.sim->step();
  }
  EXPECT_EQ(world->sumOf(world->rank() == 0 ? r.sim->particleCount() : 0), 0u) << "rank 0 kept particles";
  r.particles = gathered(*r.sim);
  expectInvariant(r, kCollapse, {}, 200);
}

TEST(Ranks, AThicknessLawsSlabIsBitIdentical) {
  RankRun r = runDistributed(test::kSamosAtSlab, {}, 150);
  expectInvariant(r, test::kSamosAtSlab, {}, 150);
}

// Each rank asks only for the lines its contact nodes read (engine/line_ranks.h): here lines
// along x, through blocks of several ranks.
TEST(Ranks, AThicknessLawOnASteepSlopeIsBitIdentical) {
  RankRun r = runDistributed(test::kSamosAtSteepSlope, {}, 150);
  expectInvariant(r, test::kSamosAtSteepSlope, {}, 150);
}

TEST(Ranks, TheDefaultTerrainSceneIsBitIdentical) {
  RankRun r = runDistributed(defaultSceneText(), {"simulation.end_time=0.3"}, 120);
  expectInvariant(r, defaultSceneText(), {"simulation.end_time=0.3"}, 120);
}

TEST(Ranks, ColliderLoadsOnRankZeroAreOneProcesssBitForBit) {
  RankRun r = runDistributed(kCollapse, {}, 100);
  if (world->rank() != 0) return;
  SceneSetup s = loadSceneString(kCollapse, "test.toml", {});
  Simulation alone(s.settings, std::move(s.groups));
  for (int i = 0; i < 100; ++i) alone.step();
  ASSERT_EQ(alone.colliderLoads().size(), r.sim->colliderLoads().size());
  for (size_t k = 0; k < alone.colliderLoads().size(); ++k) {
    // Rank 0 adds the ranks' per-block loads in one process's block order: equal, not close.
    EXPECT_EQ(alone.colliderLoads()[k].force, r.sim->colliderLoads()[k].force) << alone.colliders()[k]->name();
    EXPECT_EQ(alone.colliderLoads()[k].moment, r.sim->colliderLoads()[k].moment) << alone.colliders()[k]->name();
  }
  EXPECT_GT(alone.colliderLoads()[0].force.norm(), 0.0); // the floor carries the column
}

// A block sliding down a 30-degree plane over a thin erodible cover, a field on the terrain
// (engine/erodible_bed.h): the columns' sums over every rank's nodes and the particles the pools
// make. The block slides toward -x, into lower ranks' ranges: blocks holding new particles also
// take particles arriving from a higher rank in the same step, which one process orders first.
SceneSetup erodibleSlope() {
  const std::string toml = R"(
[simulation]
dx = 0.05
end_time = 1
[domain]
min = [0, 0, 0]
max = [3.0, 0.8, 2.2]
walls = "slip"
[terrain]
plane = { point = [3.0, 0, 1.8], normal = [-0.5, 0, 0.8660254] }
boundary = "friction"
friction = 0.5773503
[[materials]]
name = "block"
model = "elastic"
density = 1000
youngs_modulus = 1e6
poisson_ratio = 0.3
[[materials]]
name = "cover"
model = "elastic"
density = 1000
youngs_modulus = 1e6
poisson_ratio = 0.3
[[bodies]]
material = "block"
shape = "box"
center = [2.45, 0.4, 1.5979]
size = [0.4, 0.3, 0.2]
rotation = [0, -30, 0]
velocity = [-1.7320508, 0, -1]
)";
  SceneSetup s = loadSceneString(toml, "erodible.toml", {});
  ErodibleCover cover;
  cover.name = "cover";
  cover.group = 0; // the block's own material: its particles and the new ones share the arrays
  cover.erosionEnergy = 32.7;
  cover.particleMass = 1000 * 0.05 * 0.05 * 0.05 / 8;
  for (int i = 0; i <= 60; ++i)
    for (int j = 0; j <= 16; ++j) cover.columns.push_back({i, j, 50 * 0.05 * 0.05});
  s.settings.covers.push_back(cover);
  return s;
}

TEST(Ranks, AnErodibleFieldIsBitIdentical) {
  SceneSetup s = erodibleSlope();
  Simulation sim(s.settings, std::move(s.groups));
  sim.distribute(world, 0.1);
  std::unique_ptr<Simulation> view, alone; // rank 0: the gathered run, and one process's
  if (world->rank() == 0) {
    SceneSetup v = erodibleSlope(), a = erodibleSlope();
    view = std::make_unique<Simulation>(v.settings, std::move(v.groups));
    alone = std::make_unique<Simulation>(a.settings, std::move(a.groups));
  }
  // Compared every 50 steps: right after a step that made particles, too (they come after every
  // rank's others in the gathered arrays, as one process appends them).
  for (int round = 0; round < 8; ++round) {
    for (int i = 0; i < 50; ++i) {
      sim.step();
      if (alone) alone->step();
    }
    sim.gatherInto(view.get());
    if (!alone) continue;
    // Not ASSERT: rank 0 returning early would leave the others waiting in the next gather.
    const std::vector<char> a = snapshot(*alone), v = snapshot(*view);
    EXPECT_TRUE(a.size() == v.size() && std::memcmp(a.data(), v.data(), a.size()) == 0)
        << "the particles after " << (round + 1) * 50 << " steps at " << world->size() << " ranks differ from one process's";
    EXPECT_EQ(alone->bed()->entrainedMass(0), view->bed()->entrainedMass(0));
    EXPECT_EQ(alone->bed()->pooledMass(0), view->bed()->pooledMass(0));
    // Held once: arrays sized at once for every rank's particles and the bed's new ones (not
    // grown as the parts came in), then emptied as between writes; the next gather refills them.
    for (const MaterialGroup* g : view->groups()) EXPECT_EQ(g->particles.x.capacity(), g->size());
    view->releaseParticles();
  }
  if (alone) { EXPECT_GT(alone->groups()[0]->size(), 1548u + 20u) << "the pools made few particles: the test would not see their order"; }
}

// Memory per rank follows its share (issue 35): the particles, the grid with the terrain's
// per-block samples, and the terrain's level set (its values read on demand and its layout kept
// around the rank's blocks: io/terrain/vdb_level_set.h), each against one process's own
// figures on the same scene after the same steps.
TEST(Ranks, EachRanksParticlesGridAndTerrainFallWithTheRankCount) {
  const std::vector<std::string> set{"simulation.end_time=0.3"};
  RankRun r = runSeededOnRanks(defaultSceneText(), set, 60);
  std::unique_ptr<Simulation> alone;
  if (world->rank() == 0) {
    SceneSetup s = loadSceneString(defaultSceneText(), "test.toml", set);
    alone = std::make_unique<Simulation>(s.settings, std::move(s.groups));
    for (int i = 0; i < 60; ++i) alone->step();
  }
  auto oneProcess = [&](size_t (Simulation::*f)() const) { return world->maxOf(alone ? double(((*alone).*f)()) : 0.0); };
  auto largestRank = [&](size_t (Simulation::*f)() const) { return world->maxOf(double(((*r.sim).*f)())); };
  const double P = world->size();
  // Collectives: every rank evaluates each figure.
  const double oneParticles = oneProcess(&Simulation::particleBytes), oneGrid = oneProcess(&Simulation::gridBytes),
               oneTerrain = oneProcess(&Simulation::terrainBytes);
  const double particles = largestRank(&Simulation::particleBytes) / oneParticles;
  const double grid = largestRank(&Simulation::gridBytes) / oneGrid;
  const double terrain = largestRank(&Simulation::terrainBytes) / oneTerrain;
  if (world->rank() == 0)
    std::printf("[ measured ] %g ranks, the largest rank against one process: particles %.3f, grid %.3f, terrain %.3f "
                "(one process: %.0f, %.0f, %.0f bytes)\n", P, particles, grid, terrain, oneParticles, oneGrid, oneTerrain);
  // Particles: a rank's range holds its share within the rebalance threshold (0.1) and one
  // block's particles (measured 0.505 at 2 ranks, 0.253 at 4).
  EXPECT_LT(particles, 1.15 / P);
  // Grid: the owned blocks' share plus the halo and ghost blocks around the range, and the
  // terrain samples of the blocks a rank touched (measured 0.60 at 2 ranks, 0.39 at 4: about
  // 0.18 + 0.85 / P). Every rank holding the whole grid would read 1.
  EXPECT_LT(grid, 0.2 + 1.0 / P);
  // Terrain: the level set's nodes around the rank's blocks and the values it sampled there.
  // Part of it does not fall: every rank keeps a 1024-voxel node (270 KB) of the default
  // scene's small terrain (1.76 MB in one process), and the values under the release, which
  // every rank's seeding reads (measured 0.82 at 2 ranks, 0.71 at 4: about 0.61 + 0.42 / P).
  // A rank holding the whole level set, as before, would read 1 or more.
  EXPECT_LT(terrain, 0.65 + 0.5 / P);
}

int main(int argc, char** argv) {
  ::testing::InitGoogleTest(&argc, argv);
  world = worldCommunicator(&argc, &argv);
  // One thread per rank: the tests oversubscribe two cores with four ranks.
  tbb::global_control threads(tbb::global_control::max_allowed_parallelism, 1);
  if (world->rank() != 0) ::testing::GTEST_FLAG(output) = "", delete ::testing::UnitTest::GetInstance()->listeners().Release(
      ::testing::UnitTest::GetInstance()->listeners().default_result_printer());
  const int failed = RUN_ALL_TESTS();
  // Any rank's failure fails the job.
  return world->sumOf(uint64_t(failed)) ? 1 : 0;
}
