// Per-step outputs in parts (io/output/step_parts.h): the maps, the run-up map and the series
// (with a path's front, a section's crossings and a probe) made from the particles split into parts, as ranks make them, are one
// process's bit for bit, whatever the split. The split here is the hardest for sums in a fixed
// order: alternate particles, so every map cell and every material draws from both parts.
#include "engine/domain_decomposition.h"
#include "io/output/hazard_maps.h"
#include "io/output/time_series.h"
#include "io/output/water_surface_map.h"
#include "test_support.h"
#include "two_slabs.h"
#include "water_flume.h"

#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <gtest/gtest.h>

using namespace talus;

namespace {


/// `to` holds the particles of `from` with index parity `odd` (every array), at from's time.
void keepAlternate(const Simulation& from, Simulation& to, int odd) {
  for (size_t g = 0; g < from.groups().size(); ++g) {
    const MaterialGroup& src = *from.groups()[g];
    MaterialGroup& dst = *to.groups()[g];
    std::vector<uint32_t> idx;
    for (uint32_t i = uint32_t(odd); i < src.size(); i += 2) idx.push_back(i);
    std::vector<char> packed;
    packParticles(src, idx, packed);
    dst.particles.resize(0);
    dst.resizeState(0);
    appendParticles(dst, packed);
  }
  to.setTime(from.time());
}

// The slabs under gravity: they fall and spread, so the maps' cells change every step.
const std::vector<std::string> kFalling = {"simulation.gravity=[0,0,-9.81]"};

std::string_view view(const std::vector<char>& v) { return {v.data(), v.size()}; }

PartBounds mergedBounds(const Simulation& a, const Simulation& b) {
  const PartBounds x = PartBounds::of(a), y = PartBounds::of(b);
  return {std::max(x.maxMass, y.maxMass), std::max(x.maxSpeed2, y.maxSpeed2), std::max(x.maxCoord, y.maxCoord)};
}

/// One step of `parts` as rank 0 takes it with two ranks: `sim`'s alternate particles in `even`
/// (rank 0's own, kept in place) and `odd` (the other rank's, sent first), every rank's maxima.
/// Returns the sent part's size.
size_t stepInTwoParts(OutputObserver& parts, const Simulation& sim, Simulation& even, Simulation& odd, double dt) {
  keepAlternate(sim, even, 0);
  keepAlternate(sim, odd, 1);
  const PartBounds b = mergedBounds(even, odd);
  std::vector<char> sent, kept;
  parts.part(odd, b, false, sent);
  parts.part(even, b, true, kept);
  parts.onStepParts(sim, dt, b, {view(kept), view(sent)});
  return sent.size();
}

/// One step of an output by owner as two ranks take it (Run::stepOutputsOnRanks): `sim`'s
/// alternate particles in `even` (rank 0's) and `odd` (rank 1's), each sending the other's rows
/// and folding its own; rank 0 then gathers rank 1's result when one is due. Returns whether it was.
bool stepByOwnerInTwo(OutputObserver& rank0, OutputObserver& rank1, const Simulation& sim, Simulation& even,
                      Simulation& odd, double dt) {
  keepAlternate(sim, even, 0);
  keepAlternate(sim, odd, 1);
  const PartBounds b = mergedBounds(even, odd);
  std::vector<std::vector<char>> from0(2), from1(2);
  rank0.partByOwner(even, b, 0, from0);
  rank1.partByOwner(odd, b, 1, from1);
  EXPECT_TRUE(from0[0].empty() && from1[1].empty()) << "each keeps its own cells in place";
  rank0.onStepParts(sim, dt, b, {view(from0[0]), view(from1[0])});
  rank1.onStepParts(sim, dt, b, {view(from0[1]), view(from1[1])});
  EXPECT_EQ(rank0.resultDue(), rank1.resultDue()) << "rank 1 learns the film's clock from rank 0's part";
  if (!rank0.resultDue()) return false;
  std::vector<char> result;
  rank1.ownedResult(false, result);
  rank0.mergeResults(sim, false, {view(result)});
  return true;
}

/// The water flume for the run-up map: the whole run and two ranks' shares of it.
struct Flume {
  std::unique_ptr<Simulation> sim = test::makeSimulation(test::kWaterFlumeScene);
  std::unique_ptr<Simulation> even = test::makeSimulation(test::kWaterFlumeScene);
  std::unique_ptr<Simulation> odd = test::makeSimulation(test::kWaterFlumeScene);
  /// Map cells of `cell` metres over the flume's domain.
  RasterGrid grid(double cell) const {
    RunContext run;
    run.origin = sim->settings().origin;
    run.domainMin = sim->settings().domain.min, run.domainMax = sim->settings().domain.max;
    return HazardMaps::domainGrid(run, cell);
  }
};

/// Before rank 0 writes: rank 1's state merged into rank 0's.
void gatherState(OutputObserver& rank0, OutputObserver& rank1, const Simulation& sim) {
  std::vector<char> state;
  rank1.ownedResult(true, state);
  rank0.mergeResults(sim, true, {view(state)});
}

} // namespace

TEST(StepParts, MapsFromAlternateParticlesInTwoPartsAreOneProcesssBitForBit) {
  auto sim = test::makeSimulation(test::kSlabs, kFalling);
  auto even = test::makeSimulation(test::kSlabs, kFalling), odd = test::makeSimulation(test::kSlabs, kFalling);
  const std::string dir = test::tempDir("step_parts_maps");
  const auto maps1 = test::slabMaps(*sim, dir), maps2 = test::slabMaps(*sim, dir);
  HazardMaps &one = *maps1, &parts = *maps2;
  one.onStart(*sim);
  parts.onStart(*sim);
  for (int i = 0; i < 20; ++i) {
    const double dt = sim->step();
    one.onStep(*sim, dt);
    ASSERT_TRUE(parts.partDue(*sim));
    EXPECT_GT(stepInTwoParts(parts, *sim, *even, *odd, dt), 0u);
  }
  EXPECT_EQ(parts.accumulations(), one.accumulations());
  for (int layer = 0; layer < 3; ++layer)
    for (int q = 0; q < HazardMaps::Deposit; ++q) {
      const auto a = one.raster(HazardMaps::Quantity(q), layer), c = parts.raster(HazardMaps::Quantity(q), layer);
      EXPECT_EQ(std::memcmp(a.data(), c.data(), a.size() * sizeof(float)), 0) << HazardMaps::stem(HazardMaps::Quantity(q));
      EXPECT_GT(*std::max_element(a.begin(), a.end()), 0.f) << "a map that stayed empty tests nothing";
    }
}

std::string fileBytes(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), {});
}

TEST(StepParts, MapsByOwnerAtTwoRanksWithAFilmAreOneProcesssBitForBit) {
  // Two ranks as Run::stepOutputsOnRanks drives them: each sums its particles, sends the cells
  // of the other's rows and folds its own; rank 0 gathers the film's frames and, at the end,
  // the other's maxima. Rank 1 never holds rank 0's rows: no process adds every cell.
  auto sim = test::makeSimulation(test::kSlabs, kFalling);
  auto even = test::makeSimulation(test::kSlabs, kFalling), odd = test::makeSimulation(test::kSlabs, kFalling);
  const std::string dirOne = test::tempDir("step_parts_owner_one"), dirRanks = test::tempDir("step_parts_owner_ranks");
  auto filmed = [&](const std::string& dir) {
    return test::slabMaps(*sim, dir, [](MapSettings& ms) { ms.animation.enabled = true, ms.animation.interval = 0.004; });
  };
  const auto maps1 = filmed(dirOne), maps0 = filmed(dirRanks), maps1r = filmed(dirRanks);
  HazardMaps &one = *maps1, &rank0 = *maps0, &rank1 = *maps1r;
  one.onStart(*sim);
  rank0.onStart(*sim);
  rank1.prepareParts(*sim);
  ASSERT_TRUE(rank0.partsByOwner()) << "no terrain: every cell's slope is known at the start";
  int frames = 0;
  for (int i = 0; i < 20; ++i) {
    const double dt = sim->step();
    one.onStep(*sim, dt);
    ASSERT_TRUE(rank0.partDue(*sim));
    frames += stepByOwnerInTwo(rank0, rank1, *sim, *even, *odd, dt);
  }
  EXPECT_GE(frames, 3);
  const int nx = rank1.grid().nx; // the domain's grid: the window is the whole grid
  const auto own1 = rank1.raster(HazardMaps::MaxHeightVertical);
  size_t rank1Rows = 0;
  for (size_t c = 0; c < own1.size(); ++c) {
    if (!(own1[c] > 0)) continue;
    EXPECT_EQ(OutputObserver::ownerOfRow(int(c / size_t(nx)), 2), 1) << "cell " << c << " is rank 0's";
    ++rank1Rows;
  }
  EXPECT_GT(rank1Rows, 0u);
  gatherState(rank0, rank1, *sim);
  for (int layer = 0; layer < 3; ++layer)
    for (int q = 0; q < HazardMaps::Deposit; ++q) {
      const auto a = one.raster(HazardMaps::Quantity(q), layer), c = rank0.raster(HazardMaps::Quantity(q), layer);
      EXPECT_EQ(std::memcmp(a.data(), c.data(), a.size() * sizeof(float)), 0) << HazardMaps::stem(HazardMaps::Quantity(q));
    }
  size_t compared = 0; // the frames' rasters (a step longer than the interval skips an index)
  for (const auto& e : std::filesystem::directory_iterator(dirOne + "/animation/rasters")) {
    const std::string name = "/animation/rasters/" + e.path().filename().string();
    EXPECT_TRUE(fileBytes(dirOne + name) == fileBytes(dirRanks + name)) << name << " differs";
    ++compared;
  }
  EXPECT_GE(compared, size_t(frames)) << "every frame's rasters";
}

TEST(StepParts, SeriesFromAlternateParticlesInTwoPartsIsOneProcesssBitForBit) {
  auto sim = test::makeSimulation(test::kSlabs, kFalling);
  auto even = test::makeSimulation(test::kSlabs, kFalling), odd = test::makeSimulation(test::kSlabs, kFalling);
  OutputSettings os;
  os.seriesInterval = 0.005;
  // A path along the snow slab's course, its corridor wide enough for both slabs' edges.
  PathSpec path;
  path.name = "along";
  path.points = {{2600000.2, 1200001.0}, {2600003.8, 1200001.6}};
  path.halfWidth = 0.6;
  path.threshold = 0.1;
  os.paths.push_back(path);
  // A section across it just ahead of the snow slab (moving at 2 m/s), drawn from its left bank
  // to its right looking downstream: it counts crossings every step, each rank its own.
  SectionSpec across;
  across.name = "across";
  across.points = {{2600002.5, 1200001.4}, {2600002.5, 1200000.2}};
  os.sections.push_back(across);
  // A probe riding the snow slab: every rank sends its sums to every rank each step.
  ProbeSpec probe;
  probe.name = "ride";
  probe.point = {2600001.4, 1200000.8, 1000.4};
  probe.hasZ = true;
  os.probes.push_back(probe);
  const std::string dir = test::tempDir("step_parts_series");
  // `rank0` makes the rows, `rank1` only its parts, as on a process other than rank 0.
  TimeSeries one(dir, os, 0.5, 0.05), rank0(dir, os, 0.5, 0.05), rank1(dir, os, 0.5, 0.05);
  one.onStart(*sim);
  rank0.onStart(*sim);
  rank1.prepareParts(*sim);
  ASSERT_TRUE(rank0.accumulatesOnRanks()) << "the section adds up crossings between rows";
  ASSERT_TRUE(rank0.partsByOwner() && rank0.sharesState()) << "the probe moves on every rank";
  std::vector<char> state;
  rank0.shareState(state);
  rank1.takeState(view(state)); // the probe's place and the series' clock, as after the start
  for (int i = 0; i < 40; ++i) {
    const double dt = sim->step();
    one.onStep(*sim, dt);
    keepAlternate(*sim, *even, 0);
    keepAlternate(*sim, *odd, 1);
    rank0.stepLocal(*even, dt);
    rank1.stepLocal(*odd, dt);
    if (i == 20) gatherState(rank0, rank1, *sim); // a checkpoint: rank 1's totals go to rank 0
    ASSERT_TRUE(rank0.partDue(*sim)) << "a probe needs every step";
    const PartBounds b = mergedBounds(*even, *odd);
    std::vector<std::vector<char>> from0(2), from1(2);
    rank0.partByOwner(*even, b, 0, from0);
    rank1.partByOwner(*odd, b, 1, from1);
    rank0.onStepParts(*sim, dt, b, {view(from0[0]), view(from1[0])});
    rank1.onStepParts(*sim, dt, b, {view(from0[1]), view(from1[1])});
  }
  const SeriesTable &x = one.table(), &y = rank0.table();
  ASSERT_GT(x.rows.size(), 10u);
  ASSERT_EQ(x.rows.size(), y.rows.size());
  for (size_t r = 0; r < x.rows.size(); ++r)
    EXPECT_EQ(std::memcmp(x.rows[r].data(), y.rows[r].data(), x.rows[r].size() * sizeof(double)), 0) << "row " << r;
  const int front = x.column("front_m_along");
  ASSERT_GE(front, 0);
  EXPECT_GT(x.rows.back()[size_t(front)], 2.0) << "the snow slab's front, 2.2 m along the path at the start";
  // The sums are exact: the total mass is the particles' masses summed exactly, to a unit.
  const int mass = x.column("mass_kg_snow");
  ASSERT_GE(mass, 0);
  double exact = 0;
  for (Real m : sim->groups()[0]->particles.mass) exact += double(m);
  EXPECT_NEAR(x.rows.back()[size_t(mass)], exact, 1e-12 * exact);
  // The section's rows, times their intervals, add up to the snow that went past x = 2.5 m
  // (counted at the end; none comes back against 2 m/s), to the unit of its fixed-point sums.
  const int q = x.column("discharge_m3_s_across_snow");
  ASSERT_GE(q, 0);
  double crossed = 0, beyond = 0;
  for (size_t r = 1; r < x.rows.size(); ++r) crossed += x.rows[r][size_t(q)] * (x.rows[r][0] - x.rows[r - 1][0]);
  const ParticleSet& snow = sim->groups()[0]->particles;
  for (size_t p = 0; p < snow.size(); ++p) beyond += snow.x[p][0] > 2.5 ? double(snow.mass[p]) / 300 : 0.0;
  EXPECT_GT(beyond, 0.01) << "the slab has reached the section";
  EXPECT_NEAR(crossed, beyond, 1e-9 * beyond);
  // Both ranks moved the probe alike, and it rode the slab at about its 2 m/s.
  std::vector<char> state0, state1;
  rank0.shareState(state0);
  rank1.shareState(state1);
  EXPECT_TRUE(state0 == state1) << "rank 1's probe or clock is not rank 0's";
  // Downstream the probe keeps the slab's 2 m/s (it also falls, up to 2 m/s in 0.2 s, onto the
  // domain's floor: its speed is not checked); 10 % for the floor's friction once it lands.
  const int px = x.column("probe_x_m_ride");
  ASSERT_GE(px, 0);
  const double along = x.rows.back()[size_t(px)] - x.rows.front()[size_t(px)], t = x.rows.back()[0];
  EXPECT_NEAR(along / t, 2.0, 0.2) << along << " m in " << t << " s";
}

TEST(StepParts, RunUpMapFromAlternateParticlesInTwoPartsIsOneProcesssBitForBit) {
  // A water column collapsing along a flume: the surface per cell moves every step.
  Flume f;
  auto &sim = f.sim, &even = f.even, &odd = f.odd;
  const RasterGrid grid = f.grid(0.08);
  const std::string dir = test::tempDir("step_parts_runup");
  WaterSurfaceMap one(dir, grid, nullptr, {}, 0.02, false), parts(dir, grid, nullptr, {}, 0.02, false);
  one.onStart(*sim);
  parts.onStart(*sim);
  ASSERT_TRUE(parts.partDue(*sim));
  for (int i = 0; i < 30; ++i) {
    const double dt = sim->step();
    one.onStep(*sim, dt);
    stepInTwoParts(parts, *sim, *even, *odd, dt);
  }
  const auto a = one.maxSurface(), c = parts.maxSurface();
  ASSERT_EQ(a.size(), c.size());
  EXPECT_EQ(std::memcmp(a.data(), c.data(), a.size() * sizeof(float)), 0);
  EXPECT_GT(std::count_if(a.begin(), a.end(), [](float z) { return z > 0.3f; }), 0) << "the column's surface";
}

TEST(StepParts, RunUpMapByOwnerAtTwoRanksIsOneProcesssBitForBit) {
  // As above, the cells going to the rank owning their row; rank 1 never holds rank 0's rows.
  Flume f;
  auto &sim = f.sim, &even = f.even, &odd = f.odd;
  const RasterGrid grid = f.grid(0.01); // 16 rows: rank 0 owns the first 8, rank 1 the others
  const std::string dir = test::tempDir("step_parts_runup_owner");
  WaterSurfaceMap one(dir, grid, nullptr, {}, 0.02, false), rank0(dir, grid, nullptr, {}, 0.02, false),
      rank1(dir, grid, nullptr, {}, 0.02, false);
  one.onStart(*sim);
  rank0.onStart(*sim);
  rank1.prepareParts(*sim);
  for (int i = 0; i < 120; ++i) { // the front crosses cells its column did not cover
    const double dt = sim->step();
    one.onStep(*sim, dt);
    EXPECT_FALSE(stepByOwnerInTwo(rank0, rank1, *sim, *even, *odd, dt)) << "the run-up map writes nothing before the end";
  }
  const auto own1 = rank1.maxSurface();
  size_t wet = 0;
  for (size_t c = 0; c < own1.size(); ++c)
    if (!std::isnan(own1[c])) {
      EXPECT_EQ(OutputObserver::ownerOfRow(int(c / size_t(grid.nx)), 2), 1) << "cell " << c << " is rank 0's";
      ++wet;
    }
  EXPECT_GT(wet, 0u) << "rank 1 owns half the flume's width";
  const auto before = rank0.maxSurface(), whole = one.maxSurface();
  EXPECT_NE(std::memcmp(before.data(), whole.data(), whole.size() * sizeof(float)), 0)
      << "rank 0 lacks rank 1's rows wetted since the start until it gathers them: else this tests nothing";
  gatherState(rank0, rank1, *sim);
  const auto a = one.maxSurface(), c = rank0.maxSurface();
  ASSERT_EQ(a.size(), c.size());
  EXPECT_EQ(std::memcmp(a.data(), c.data(), a.size() * sizeof(float)), 0);
}
