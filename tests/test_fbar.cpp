// F-bar (SimulationSettings::fbar, engine/fbar.h): a solid particle's volume change per step is
// the grid's mass-weighted average around it. It must leave a homogeneous deformation exactly as it
// is, remove particle-scale volume changes (the pressure checkerboard of locking), keep the mean
// compression, and stay bit-identical over thread counts.
#include "small_collapse.h"
#include "test_support.h"

#include <cmath>
#include <cstring>
#include <gtest/gtest.h>
#include <random>
#include <tbb/global_control.h>

using namespace talus;

namespace {

// A stress-free elastic block far from every wall, no gravity: only the initial velocities act.
const char* kBlock = R"(
[simulation]
dx = 0.05
end_time = 1
gravity = [0, 0, 0]
max_dt = 1e-3
[domain]
min = [0, 0, 0]
max = [1, 1, 1]
[[materials]]
name = "block"
model = "elastic"
density = 1000
youngs_modulus = 1e5
poisson_ratio = 0.45
[[bodies]]
material = "block"
shape = "box"
min = [0.3, 0.3, 0.3]
max = [0.7, 0.7, 0.7]
)";

struct Spread {
  double mean = 0, rms = 0; ///< of the particles' pressure (Pa)
};

/// Over the particles at least 2 dx inside the block (its surface layer deforms differently).
Spread pressureSpread(const Simulation& sim) {
  const MaterialGroup& g = *sim.groups()[0];
  std::vector<float> all, p;
  g.scalar("pressure", all);
  for (size_t i = 0; i < all.size(); ++i)
    if ((g.particles.x[i] - Vec3(0.5f, 0.5f, 0.5f)).cwiseAbs().maxCoeff() < 0.1f) p.push_back(all[i]);
  Spread s;
  for (float v : p) s.mean += v;
  s.mean /= double(p.size());
  for (float v : p) s.rms += (v - s.mean) * (v - s.mean);
  s.rms = std::sqrt(s.rms / double(p.size()));
  return s;
}

/// One step from velocities `init` (per particle, from its position).
template <class Init>
std::unique_ptr<Simulation> oneStep(bool fbar, Init init) {
  auto sim = test::makeSimulation(kBlock, {std::string("simulation.fbar=") + (fbar ? "true" : "false")});
  for (MaterialGroup* g : sim->groups())
    for (size_t p = 0; p < g->size(); ++p) init(g->particles, p);
  sim->step(1e-3);
  return sim;
}

} // namespace

TEST(Fbar, LeavesAHomogeneousDeformationAsItIs) {
  // v = A x with C = A: APIC carries the affine field to the nodes exactly and gathers it back, so
  // every particle's volume change equals the mean and F-bar's factor is 1 (float rounding).
  Mat3 A;
  A << 0.5, 0.2, 0, -0.1, 0.3, 0.1, 0, 0.2, -0.4;
  auto affine = [&](ParticleSet& P, size_t p) {
    P.v[p] = A * (P.x[p] - Vec3(0.5, 0.5, 0.5));
    P.C[p] = A;
  };
  const auto off = oneStep(false, affine), on = oneStep(true, affine);
  const Spread a = pressureSpread(*off), b = pressureSpread(*on);
  // The step stretches by tr A dt = 4e-4: mean pressure -K 4e-4 = -133 Pa (K = 333 kPa).
  ASSERT_GT(std::abs(a.mean), 10.0);
  // 1e-4 relative: float rounding of the factor (1e-7) against a 4e-4 volume change.
  std::printf("  mean pressure %.6g Pa without, %.6g Pa with F-bar\n", a.mean, b.mean);
  EXPECT_NEAR(b.mean, a.mean, 1e-4 * std::abs(a.mean));
  EXPECT_LT(a.rms, 1e-2 * std::abs(a.mean)); // homogeneous: no spread with or without
  EXPECT_LT(b.rms, 1e-2 * std::abs(a.mean));
}

TEST(Fbar, RemovesParticleScaleVolumeChangesAndKeepsTheMean) {
  // Independent random velocities: each particle's own divergence is noise at the particle scale,
  // the pressure checkerboard a locked flow shows. F-bar replaces it with the mean over the ~27
  // nodes of its stencil, which holds little of it; the body's mean compression stays.
  std::mt19937 rng;
  auto noisy = [&rng](ParticleSet& P, size_t p) {
    if (p == 0) rng.seed(11); // the same noise for both runs
    std::normal_distribution<float> n(0.f, 0.1f);
    P.v[p] = Vec3(n(rng), n(rng), n(rng)) + 0.5f * (P.x[p] - Vec3(0.5f, 0.5f, 0.5f)); // noise + expansion
  };
  const auto off = oneStep(false, noisy), on = oneStep(true, noisy);
  const Spread a = pressureSpread(*off), b = pressureSpread(*on);
  std::printf("  pressure mean / rms: own volume change %.3g / %.3g Pa, F-bar %.3g / %.3g Pa\n", a.mean, a.rms,
              b.mean, b.rms);
  // The spread falls by the averaging over ~27 nodes of ~8 particles each: measured 110 -> 36 Pa
  // (3.1x) inside the block. Asserting 2x leaves room for the seed; without the averaging the two
  // would be equal.
  EXPECT_LT(b.rms, 0.5 * a.rms);
  // Mean: the mass-weighted mean of ΔJ - 1 is what the average conserves; the pressure's mean
  // differs from it by the spread's second-order term. 10 % of the mean.
  EXPECT_NEAR(b.mean, a.mean, 0.1 * std::abs(a.mean));
}

TEST(Fbar, OneAndTwoThreadsGiveBitIdenticalParticles) {
  auto run = [](int threads) {
    tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
    auto sim = test::makeSimulation(test::kSmallCollapse, {"simulation.fbar=true"});
    for (int s = 0; s < 60; ++s) sim->step();
    return test::particleBytes(*sim);
  };
  EXPECT_EQ(run(1), run(2));
}

TEST(Fbar, PeriodicAxesAreRefusedWithAMessage) {
  try {
    test::makeSimulation(test::kSmallCollapse, {"simulation.fbar=true", "domain.periodic=[\"y\"]"});
    FAIL() << "accepted";
  } catch (const std::exception& e) {
    EXPECT_NE(std::string(e.what()).find("fbar"), std::string::npos) << e.what();
  }
}
