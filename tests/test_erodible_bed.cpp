// Erodible covers as fields on the terrain (engine/erodible_bed.h), against a closed form.
//
// A block slides over a uniform cover on a plane at 30 degrees with Coulomb friction mu =
// tan 30: gravity and friction balance for every particle, the block's and the eroded cover's,
// so the momentum along the slope P of the flow and the pools is constant, P = M0 u0. The
// erosion rate is AvaFrame's tau u / e_b: the friction mu N times the speed over e_b, summed
// over what slides, dM/dt = k P_flowing with k = mu g cos(theta) / e_b. With the pools' share
// small, M(t) = k M0 u0 t. Mass is conserved to round-off, and a column the flow never reaches
// keeps every kilogram.
#include "engine/simulation.h"
#include "io/run/checkpoint.h"
#include "io/scene/scene.h"
#include "io/terrain/terrain_loader.h"
#include "terrain_test_support.h"
#include "test_support.h"

#include <cmath>
#include <cstdio>
#include <gtest/gtest.h>
#include <tbb/global_control.h>

using namespace talus;

namespace {

constexpr double kTheta = 30.0 * M_PI / 180.0, kG = 9.81, kDx = 0.05, kU0 = 2.0;
const double kMu = std::tan(kTheta);
constexpr double kEnergy = 32.7; // J/kg: k = mu g cos(theta) / e_b = 0.150 per m

struct Slope {
  std::unique_ptr<Simulation> sim;
  double M0 = 0, bedMass = 0;
};

/// The block (0.4 x 0.3 x 0.2 m, 1000 kg/m3) moving at u0 down the plane, over a cover of 50
/// kg/m2 at every node column of the plane's first 3 m and 0.8 m across.
Slope build(double frictionOverride = -1, double u0 = kU0, double gravityRamp = 0) {
  const Vec3d n(std::sin(kTheta), 0, std::cos(kTheta)), s(std::cos(kTheta), 0, -std::sin(kTheta));
  const Vec3d p0(0.5, 0.4, 1.8 - std::tan(kTheta) * 0.5), c = p0 + 0.1 * n;
  const double mu = frictionOverride >= 0 ? frictionOverride : kMu;
  char toml[2048];
  std::snprintf(toml, sizeof toml, R"(
[simulation]
dx = %.9g
end_time = 1
gravity_ramp = %.9g
[domain]
min = [0, 0, 0]
max = [3.0, 0.8, 2.2]
walls = "slip"
[terrain]
plane = { point = [0, 0, 1.8], normal = [%.9g, 0, %.9g] }
boundary = "friction"
friction = %.9g
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
center = [%.9g, %.9g, %.9g]
size = [0.4, 0.3, 0.2]
rotation = [0, 30, 0]
velocity = [%.9g, 0, %.9g]
)",
                kDx, gravityRamp, n.x(), n.z(), mu, c.x(), c.y(), c.z(), u0 * s.x(), u0 * s.z());
  SceneSetup setup = loadSceneString(toml, "slope.toml");
  ErodibleCover cover;
  cover.name = "cover";
  cover.group = 1;
  cover.erosionEnergy = kEnergy;
  cover.particleMass = 1000 * kDx * kDx * kDx / 8;
  Slope out;
  for (int i = 0; i <= 60; ++i)
    for (int j = 0; j <= 16; ++j) {
      cover.columns.push_back({i, j, 50 * kDx * kDx});
      out.bedMass += 50 * kDx * kDx;
    }
  setup.settings.covers.push_back(cover);
  out.sim = std::make_unique<Simulation>(setup.settings, std::move(setup.groups));
  out.M0 = out.sim->totalMass();
  return out;
}

/// Momentum along the slope of the particles (flowing) and of the pools.
double slopeMomentum(const Simulation& sim) {
  const Vec3d s(std::cos(kTheta), 0, -std::sin(kTheta));
  return sim.linearMomentum().dot(s);
}

} // namespace

TEST(ErodibleBed, EntrainsAtTheShearPowerOverTheErosionEnergyAndConservesMass) {
  Slope sl = build();
  Simulation& sim = *sl.sim;
  const ErodibleBed& bed = *sim.bed();
  const double P0 = slopeMomentum(sim), k = kMu * kG * std::cos(kTheta) / kEnergy;
  double predicted = 0, pPrev = P0, tPrev = 0, worstLedger = 0, worstP = 0;
  for (int i = 1; i <= 40; ++i) {
    const double t = 0.02 * i;
    sim.advanceTo(t);
    // What erodes is what slides: the particles' momentum (the pools wait, and do not erode).
    const double p = slopeMomentum(sim);
    predicted += 0.5 * k * (p + pPrev) * (t - tPrev);
    pPrev = p, tPrev = t;
    const double ledger = sim.totalMass() + bed.remainingMass(0) + bed.pooledMass(0) - (sl.M0 + sl.bedMass);
    worstLedger = std::max(worstLedger, std::abs(ledger) / (sl.M0 + sl.bedMass));
    const Vec3d pool = bed.pooledMomentum(0);
    const double total = p + pool.dot(Vec3d(std::cos(kTheta), 0, -std::sin(kTheta)));
    worstP = std::max(worstP, std::abs(total / P0 - 1));
  }
  const double entrained = bed.entrainedMass(0), closed = k * P0 * 0.8;
  std::printf("  entrained %.5f kg (%.1f %% of the block), rate integral %.5f kg (%+.2f %%), closed form k M0 u0 t "
              "%.5f kg (%+.2f %%); momentum along the slope within %.2f %%; mass ledger %.2e\n",
              entrained, 100 * entrained / sl.M0, predicted, 100 * (entrained / predicted - 1), closed,
              100 * (entrained / closed - 1), 100 * worstP, worstLedger);
  // The erosion law itself: the mass taken against the shear power the run's own speeds give.
  // 3 %: the block's normal force rings (elastic, loaded at once), which the rate follows.
  EXPECT_NEAR(entrained / predicted, 1.0, 0.03);
  // Against the closed form: also what waits in pools (a few per cent of the mass) is not
  // eroding, so 6 %.
  EXPECT_NEAR(entrained / closed, 1.0, 0.06);
  // Momentum of flow plus pools: gravity balances friction on every particle. The sliding
  // block alone keeps its speed within 2 % (tests/test_sliding_block.cpp); 3 % with the new
  // particles joining in.
  EXPECT_LT(worstP, 0.03);
  // Mass: the field's, the pools' and the particles' add up to the start to round-off (float
  // particle masses: 1e-7 of each, a few hundred particles).
  EXPECT_LT(worstLedger, 1e-6);
  EXPECT_GT(sim.groups()[1]->size(), 50u) << "the eroded mass became particles of the cover";
  // Columns the flow never reached (the far side, 0.2 m beyond the block's edge) keep every kilogram.
  for (int i = 0; i <= 60; ++i)
    for (int j = 15; j <= 16; ++j) ASSERT_EQ(bed.erodedMass(i, j, 0), 0.0) << i << " " << j;
}

TEST(ErodibleBed, ABlockHeldByStaticFrictionErodesAlmostNothing) {
  // mu = 0.7 > tan 30, the block at rest and gravity ramped in over 0.2 s (a sudden load makes
  // the elastic block ring and slip: tests/test_sliding_block.cpp). Its elastic settling moves
  // it about 0.5 mm, so what it erodes is a trace: asserted under 1e-3 of what the sliding block
  // of the test above takes in the same 0.8 s (5.6 kg), and nothing at all once settled.
  Slope sl = build(0.7, 0.0, 0.2);
  sl.sim->advanceTo(0.8);
  const double settled = sl.sim->bed()->entrainedMass(0);
  std::printf("  held block: %.3g kg eroded in 0.8 s\n", settled);
  EXPECT_LT(settled, 5.6e-3);
}

TEST(ErodibleBed, ResumesBitForBit) {
  const std::string dir = test::tempDir("erodible_bed_resume");
  Slope a = build(), b = build();
  a.sim->advanceTo(0.2);
  const CheckpointIdentity id{"0123456789abcdef"};
  writeCheckpoint(checkpointPath(dir), *a.sim, id);
  readCheckpoint(checkpointPath(dir), *b.sim, id);
  a.sim->advanceTo(0.4);
  b.sim->advanceTo(0.4);
  EXPECT_EQ(a.sim->bed()->entrainedMass(0), b.sim->bed()->entrainedMass(0));
  EXPECT_EQ(a.sim->bed()->pooledMass(0), b.sim->bed()->pooledMass(0));
  ASSERT_EQ(a.sim->groups()[1]->size(), b.sim->groups()[1]->size());
  for (size_t p = 0; p < a.sim->groups()[1]->size(); ++p)
    ASSERT_EQ(a.sim->groups()[1]->particles.x[p], b.sim->groups()[1]->particles.x[p]);
}

TEST(ErodibleBed, AThinLayerBecomesAFieldAndAThickOneParticles) {
  // A flat DEM (1 m cells), dx 1 m: a 0.3 m cover over 20 x 20 m is a field of 21 x 21 node
  // columns less the 9 x 9 under a 9.6 x 9.6 m release that lies on it (AvaFrame crops
  // entrainment areas by release areas), 300 kg/m3 x 0.3 m x 1 m2 each; with field_below = 0
  // the same cover is particles.
  test::useTestTerrainCache();
  const std::string dir = test::tempDir("erodible_bed_scene");
  constexpr double X0 = 2600000, Y0 = 1200000;
  const std::string dem = dir + "/flat.tif";
  writeDemGeoTiff(test::makeDem(60, 60, 1, X0, Y0, [](double, double) { return 1000.0; }), dem);
  auto box = [&](double x0, double y0, double x1, double y1) {
    char b[160];
    std::snprintf(b, sizeof b, "[%.3f, %.3f, %.3f, %.3f]", X0 + x0, Y0 + y0, X0 + x1, Y0 + y1);
    return std::string(b);
  };
  auto text = [&](const std::string& coverExtra) {
    return "[simulation]\ndx = 1\nend_time = 1\n[terrain]\ndem = \"" + dem +
           "\"\nboundary = \"friction\"\nfriction = 0.3\n[[materials]]\nname = \"snow\"\nmodel = \"elastic\"\n"
           "density = 300\nyoungs_modulus = 1e6\n[[bodies]]\nname = \"release\"\nkind = \"layer\"\nmaterial = \"snow\"\n"
           "thickness = 2\nbounds = " + box(20.2, 20.2, 29.8, 29.8) + "\n[[bodies]]\nname = \"cover\"\nkind = \"layer\"\n"
           "material = \"snow\"\nthickness = 0.3\nthickness_direction = \"vertical\"\nbounds = " +
           box(19.5, 19.5, 40.5, 40.5) + "\n" + coverExtra;
  };
  const SceneSetup field = loadSceneString(text("erosion_energy = 2000\n"), "field.toml");
  ASSERT_EQ(field.settings.covers.size(), 1u);
  const ErodibleCover& c = field.settings.covers[0];
  EXPECT_EQ(c.name, "cover");
  EXPECT_EQ(c.erosionEnergy, 2000);
  EXPECT_EQ(c.columns.size(), size_t(21 * 21 - 9 * 9));
  for (const auto& col : c.columns) ASSERT_NEAR(col.mass, 300 * 0.3, 1e-3);
  EXPECT_EQ(field.bodies[1].particles, 0u);
  bool noted = false;
  for (const auto& n : field.notes) noted |= n.find("cover: 0.3 m thick") != std::string::npos && n.find("erodible field") != std::string::npos;
  EXPECT_TRUE(noted);

  const SceneSetup particles = loadSceneString(text("field_below = 0\n"), "particles.toml");
  EXPECT_TRUE(particles.settings.covers.empty());
  EXPECT_GT(particles.bodies[1].particles, 0u);

  try {
    loadSceneString(text("field_below = -1\n"), "bad.toml");
    FAIL() << "a negative field_below was accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("field_below"), std::string::npos) << e.what();
  }
}

TEST(ErodibleBed, BitIdenticalAtOneAndTwoThreads) {
  // Erosion and release visit nodes and columns in a fixed order; the particles they add are
  // the same, bit for bit, whatever the engine's thread count.
  auto runWith = [](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    Slope s = build();
    s.sim->advanceTo(0.3);
    return s;
  };
  const Slope one = runWith(1), two = runWith(2);
  EXPECT_EQ(one.sim->bed()->entrainedMass(0), two.sim->bed()->entrainedMass(0));
  for (size_t g = 0; g < 2; ++g) {
    const ParticleSet &a = one.sim->groups()[g]->particles, &b = two.sim->groups()[g]->particles;
    ASSERT_EQ(a.size(), b.size());
    for (size_t p = 0; p < a.size(); ++p) {
      ASSERT_EQ(a.x[p], b.x[p]) << g << " " << p;
      ASSERT_EQ(a.v[p], b.v[p]) << g << " " << p;
    }
  }
}
