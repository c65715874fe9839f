// The solid update in SIMD lanes (materials/solid_lanes.h) against the scalar updateSolid, on
// random states, on every Highway target this machine runs.
#include "materials/mu_i.h"
#include "materials/solid_lanes.h"
#include "simd_targets.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>

namespace talus {
namespace {

/// Random particles around the usual path's border: F^E up to 0.2 from the identity (|b - I|
/// spans 0 to ~0.5, so about a third leave the usual path), steps with dt |C| up to 0.05, F-bar
/// scales within 2 %, and accumulated strains.
struct RandomStates {
  static constexpr int kChunks = 400;
  std::vector<SolidLanes> chunks;
  std::vector<int> counts;

  explicit RandomStates(unsigned seed, double pressureBias) : chunks(kChunks), counts(kChunks) {
    std::mt19937_64 rng(seed);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int c = 0; c < kChunks; ++c) {
      SolidLanes& io = chunks[size_t(c)];
      std::memset(&io, 0, sizeof io);
      counts[size_t(c)] = 1 + c % kSolidLanes; // every count, the partial lane groups included
      for (int k = 0; k < kSolidLanes; ++k) {
        const double spread = 0.2 * std::abs(u(rng));
        for (int r = 0; r < 9; ++r) {
          // float values, as the particle set stores them
          io.F[r][k] = double(float((r % 4 == 0 ? 1 + pressureBias : 0.0) + spread * u(rng)));
          io.C[r][k] = double(float(50 * u(rng)));
        }
        io.fbar[k] = c % 2 ? 1.0 : 1 + 0.02 * u(rng);
        io.strain[k] = double(float(0.5 * std::abs(u(rng))));
      }
    }
  }
};

constexpr double kDt = 1e-3;

/// The scalar path's result for lane k of `in` (its trial F formed as SolidGroup's scalar path does).
template <class Model>
void scalarUpdate(const Model& model, const SolidLanes& in, int k, Mat3& F, Sym3& tau, typename Model::State& s) {
  Mat3 C, F0;
  for (int r = 0; r < 9; ++r) C(r / 3, r % 3) = Real(in.C[r][k]), F0(r / 3, r % 3) = Real(in.F[r][k]);
  const Mat3d Ftrial = (in.fbar[k] * (Mat3d::Identity() + kDt * C.cast<double>())) * F0.cast<double>();
  setLaneState(s, in.strain[k], in.extra[k]);
  updateSolid(model, Ftrial, s, F, tau, kDt);
}

/// |a - b| within `ulps` units of a float's last place of the largest of `scale` (the results are
/// stored as floats; the two paths differ only in the last bits of the doubles they round from).
::testing::AssertionResult closeAsFloats(double a, double b, double scale, double ulps, const char* what) {
  const double tol = ulps * std::ldexp(1.0, -23) * std::max(scale, 1e-30);
  if (std::abs(a - b) <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << what << ": lanes " << a << ", scalar " << b << ", tolerance " << tol;
}

struct Tally {
  int usual = 0, offPath = 0, plastic = 0, tip = 0;
};

/// Runs every chunk through updateSolidLanes and holds each usual-path lane against updateSolid.
template <class Model>
Tally checkAgainstScalar(const Model& model, const RandomStates& states, std::vector<SolidLanes>& out) {
  SolidLaneParams prm;
  EXPECT_TRUE(solidLaneParams(model, prm));
  Tally tally;
  out = states.chunks;
  for (size_t c = 0; c < out.size(); ++c) {
    updateSolidLanes(prm, kDt, states.counts[c], out[c]);
    for (int k = 0; k < states.counts[c]; ++k) {
      Mat3 F;
      Sym3 tau;
      typename Model::State s{};
      scalarUpdate(model, states.chunks[c], k, F, tau, s);
      if (out[c].scalar[k] != 0) {
        ++tally.offPath;
        continue;
      }
      ++tally.usual;
      const double fScale = F.cwiseAbs().maxCoeff();
      for (int r = 0; r < 9; ++r)
        EXPECT_TRUE(closeAsFloats(double(Real(out[c].F[r][k])), double(F(r / 3, r % 3)), fScale, 2, "F"));
      const double t[6] = {tau.xx, tau.yy, tau.zz, tau.xy, tau.xz, tau.yz};
      double tScale = 0;
      for (double v : t) tScale = std::max(tScale, std::abs(v));
      for (int r = 0; r < 6; ++r) EXPECT_TRUE(closeAsFloats(double(Real(out[c].tau[r][k])), t[r], tScale, 2, "tau"));
      typename Model::State s0{};
      setLaneState(s0, states.chunks[c].strain[k], states.chunks[c].extra[k]);
      double e0, e, y0, y;
      laneState(s0, e0, y0);
      laneState(s, e, y);
      EXPECT_TRUE(closeAsFloats(double(float(out[c].extra[k])), y, std::max(std::abs(y), 1.0), 2, "second state variable"));
      if (e == e0 && y == y0) continue;
      ++tally.plastic;
      if (std::abs(tau.xy) + std::abs(tau.xz) + std::abs(tau.yz) == 0) ++tally.tip;
      EXPECT_TRUE(closeAsFloats(double(float(out[c].strain[k])), e, std::max(e, 1.0), 2, "plastic strain"));
    }
  }
  return tally;
}

/// Bit for bit the same lanes on every target this machine runs.
void expectSameOnEveryTarget(const SolidLaneParams& prm, const RandomStates& states, const std::vector<SolidLanes>& best) {
  forEachSimdTarget([&] {
    for (size_t c = 0; c < states.chunks.size(); ++c) {
      SolidLanes io = states.chunks[c];
      updateSolidLanes(prm, kDt, states.counts[c], io);
      for (int k = 0; k < states.counts[c]; ++k) {
        ASSERT_EQ(io.scalar[k], best[c].scalar[k]);
        for (int r = 0; r < 9; ++r) ASSERT_EQ(std::memcmp(&io.Ftrial[r][k], &best[c].Ftrial[r][k], 8), 0);
        if (io.scalar[k] != 0) continue;
        for (int r = 0; r < 9; ++r) ASSERT_EQ(std::memcmp(&io.F[r][k], &best[c].F[r][k], 8), 0) << "chunk " << c;
        for (int r = 0; r < 6; ++r) ASSERT_EQ(std::memcmp(&io.tau[r][k], &best[c].tau[r][k], 8), 0) << "chunk " << c;
        ASSERT_EQ(std::memcmp(&io.strain[k], &best[c].strain[k], 8), 0);
        ASSERT_EQ(io.extra[k], best[c].extra[k]);
      }
    }
  });
}

/// Both checks for one model; the tally, for the caller to see that the states exercised it.
template <class Model>
Tally checkModel(const Model& model, RandomStates states) {
  // The lanes start from what a state stores (Cam Clay's eps_v carries its flag in the last bit).
  for (auto& chunk : states.chunks)
    for (int k = 0; k < kSolidLanes; ++k) {
      typename Model::State s{};
      setLaneState(s, chunk.strain[k], chunk.extra[k]);
      laneState(s, chunk.strain[k], chunk.extra[k]);
    }
  std::vector<SolidLanes> out;
  const Tally t = checkAgainstScalar(model, states, out);
  EXPECT_GT(t.usual, 1000);
  EXPECT_GT(t.offPath, 100) << "the scalar path's lanes are exercised";
  SolidLaneParams prm;
  solidLaneParams(model, prm);
  expectSameOnEveryTarget(prm, states, out);
  return t;
}

TEST(SolidLanes, ElasticMatchesTheScalarUpdateWithinTwoFloatUlpsAndEveryTargetBitForBit) {
  ElasticModel model;
  model.elastic = HenckyElasticity::fromYoung(1e8, 0.3);
  EXPECT_EQ(checkModel(model, RandomStates(1, 0.0)).plastic, 0);
}

TEST(SolidLanes, DruckerPragerMatchesTheScalarReturnAndEveryTargetBitForBit) {
  // Cohesive, so that stretched particles (the positive bias of F) reach the tension tip.
  DruckerPragerParams p;
  p.frictionAngle = p.residualFrictionAngle = 35 * M_PI / 180;
  p.cohesion = 2e4;
  const DruckerPragerModel model(HenckyElasticity::fromYoung(1e8, 0.3), p);
  for (double bias : {-0.01, 0.01}) {
    SCOPED_TRACE(bias);
    const Tally t = checkModel(model, RandomStates(2, bias));
    EXPECT_GT(t.plastic, 500) << "most random states are far outside the cone";
    if (bias > 0) { EXPECT_GT(t.tip, 10) << "stretched states return to the tip"; }
  }
}

TEST(SolidLanes, CamClayMatchesTheScalarReturnAndEveryTargetBitForBit) {
  // The paper's snow (physics.md table: E 3 MPa, nu 0.3, M 1.2, Ms 0.4, beta 0.4, xi 0.1) at a
  // small p0, so that most random states are outside the ellipse, some compacting (p0 grows),
  // some dilating to no strength at all (p0 = 0); half the particles yielded before.
  CamClayModel model;
  model.elastic = HenckyElasticity::fromYoung(3e6, 0.3);
  model.params.p0 = 5e3;
  RandomStates states(3, 0.0);
  const double ev0 = model.initialVolumetricStrain();
  for (size_t c = 0; c < states.chunks.size(); ++c)
    for (int k = 0; k < kSolidLanes; ++k) {
      states.chunks[c].strain[k] = double(float(ev0 * (k % 3 == 0 ? 0.1 : 1.0)));
      states.chunks[c].extra[k] = k % 2;
    }
  EXPECT_GT(checkModel(model, states).plastic, 500);
}

TEST(SolidLanes, SofteningDruckerPragerMatchesTheScalarNewtonAndEveryTargetBitForBit) {
  // Table 1's rock (c 2 MPa, phi 50 -> 30 deg) with a gradual softening (chi 20) and brittle
  // (chi 1e10, Vajont's and Cengalo's: the strength is lost on first yield), on each cone fit;
  // strains of half the particles start at 0 (intact), the others up to 0.5 (softened).
  for (double chi : {20.0, 1e10})
    for (DruckerPragerCone cone : {DruckerPragerCone::Compression, DruckerPragerCone::PlaneStrain, DruckerPragerCone::Extension}) {
      SCOPED_TRACE(chi);
      SCOPED_TRACE(int(cone));
      DruckerPragerParams p;
      p.frictionAngle = 50 * M_PI / 180, p.residualFrictionAngle = 30 * M_PI / 180;
      p.cohesion = 2e5, p.softening = chi, p.cone = cone;
      const DruckerPragerModel model(HenckyElasticity::fromYoung(3e7, 0.25), p);
      SolidLaneParams prm;
      ASSERT_TRUE(solidLaneParams(model, prm));
      EXPECT_EQ(prm.kind, SolidLaneParams::Kind::SofteningDruckerPrager);
      for (double bias : {-0.01, 0.01}) {
        RandomStates states(4, bias);
        for (auto& io : states.chunks)
          for (int k = 0; k < kSolidLanes; k += 2) io.strain[k] = 0;
        const Tally t = checkModel(model, states);
        EXPECT_GT(t.plastic, 300);
        if (bias > 0) { EXPECT_GT(t.tip, 10) << "stretched states return to the tip"; }
      }
    }
}

TEST(SolidLanes, MuIMatchesTheScalarReturnAndEveryTargetBitForBit) {
  // Jop et al.'s glass beads (the model's defaults) in a stiff elastic skeleton: compressed states
  // slide at every inertial number, stretched ones go to the stress-free tip.
  MuIModel model;
  model.elastic = HenckyElasticity::fromYoung(1e7, 0.3);
  for (double bias : {-0.02, 0.01}) {
    SCOPED_TRACE(bias);
    const Tally t = checkModel(model, RandomStates(5, bias));
    EXPECT_GT(t.plastic, 500);
    if (bias > 0) { EXPECT_GT(t.tip, 10) << "unconfined states go to the tip"; }
  }
}

} // namespace
} // namespace talus
