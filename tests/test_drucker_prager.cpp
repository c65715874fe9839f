// Drucker-Prager return mapping with strain softening, tested alone (physics.md 4.1).
#include "materials/drucker_prager.h"

#include <gtest/gtest.h>
#include <random>

using namespace talus;

namespace {
DruckerPragerModel makeModel(double phiIni, double phiRes, double c, double chi,
                             DruckerPragerCone cone = DruckerPragerCone::Compression) {
  DruckerPragerParams p;
  p.frictionAngle = phiIni * M_PI / 180;
  p.residualFrictionAngle = phiRes * M_PI / 180;
  p.cohesion = c;
  p.softening = chi;
  p.cone = cone;
  return DruckerPragerModel(HenckyElasticity::fromYoung(30e6, 0.25), p);
}

double stressScale(const DruckerPragerModel& m, const Vec3d& eps) {
  const double tr = eps.sum();
  return std::sqrt(1.5) * 2 * m.elastic.mu * (eps - Vec3d::Constant(tr / 3)).norm() +
         m.elastic.bulk() * std::abs(tr) + m.params().cohesion + 1.0;
}
} // namespace

TEST(DruckerPrager, ReturnLandsOnTheSurfaceKeepsAdmissibleStatesAndIsIdempotent) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> strain(-0.05, 0.05), unit(0, 1);
  // Constant strength (fast path) and softening (consistent Newton return), all three cones.
  const DruckerPragerModel models[] = {makeModel(30, 30, 0, 0),
                                       makeModel(42, 36, 2e6, 1e10),
                                       makeModel(50, 30, 1e5, 20),
                                       makeModel(40, 25, 1e6, 3, DruckerPragerCone::PlaneStrain),
                                       makeModel(35, 20, 5e5, 10, DruckerPragerCone::Extension),
                                       makeModel(33, 33, 2e4, 0, DruckerPragerCone::PlaneStrain)};
  int plastic = 0, elastic = 0, tip = 0;
  for (const auto& m : models)
    for (int t = 0; t < 20000; ++t) {
      Vec3d eps(strain(rng), strain(rng), strain(rng));
      eps *= std::pow(10.0, -4 * unit(rng)); // strains from 5e-2 down to 5e-6
      DruckerPragerModel::State s;
      s.plasticStrain = float(unit(rng) < 0.5 ? 0.0 : 0.1 * unit(rng));
      const Vec3d trial = eps;
      const DruckerPragerModel::State s0 = s;
      const double scale = stressScale(m, trial);
      if (!m.project(eps, s, 1e-3)) {
        EXPECT_LE(m.yield(trial, s0.plasticStrain), 1e-9 * scale);
        EXPECT_EQ(eps, trial); // admissible: untouched
        ++elastic;
        continue;
      }
      ++plastic;
      EXPECT_GE(s.plasticStrain, s0.plasticStrain);
      EXPECT_LE(std::abs(m.yield(eps, s.plasticStrain)), 1e-6 * scale) << "model " << &m - models;
      const bool atTip = (eps - Vec3d::Constant(eps.sum() / 3)).norm() < 1e-14;
      if (atTip) ++tip;
      else EXPECT_NEAR(eps.sum(), trial.sum(), 1e-12); // volume-preserving flow
      // Deviatoric strain removed = plastic strain gained.
      const double devTr = (trial - Vec3d::Constant(trial.sum() / 3)).norm();
      const double devNew = (eps - Vec3d::Constant(eps.sum() / 3)).norm();
      EXPECT_NEAR(s.plasticStrain - s0.plasticStrain, devTr - devNew, 1e-6 * devTr + 1e-7 * s.plasticStrain);
      // Idempotent: projecting the result again changes nothing (beyond float storage of e).
      Vec3d again = eps;
      DruckerPragerModel::State s2 = s;
      m.project(again, s2, 1e-3);
      EXPECT_LE((again - eps).norm(), 1e-6 * (devTr + std::abs(trial.sum())));
    }
  EXPECT_GT(plastic, 10000);
  EXPECT_GT(elastic, 1000);
  EXPECT_GT(tip, 100);
}

TEST(DruckerPrager, SofteningFollowsEquationsSevenAndEight) {
  const auto m = makeModel(50, 30, 2e6, 20);
  for (double e : {0.0, 0.01, 0.05, 0.2, 1.0}) {
    EXPECT_NEAR(m.frictionAngle(e), (30 + 20 * std::exp(-20 * e)) * M_PI / 180, 1e-14);
    EXPECT_NEAR(m.cohesion(e), 2e6 * std::exp(-20 * e), 1e-6);
  }
  // gamma = 6 sin(phi) / (3 - sin(phi)): 30 degrees gives 6*0.5/2.5 = 1.2.
  EXPECT_NEAR(DruckerPragerModel::gammaOf(M_PI / 6), 1.2, 1e-14);
}

TEST(DruckerPrager, BrittleChi1e10LosesPeakStrengthOnFirstYieldWithoutBlowUp) {
  const auto m = makeModel(42, 36, 2e6, 1e10);
  // Pure shear just beyond the intact surface at zero pressure: q = gamma c (1 + 1e-3).
  const double k = std::sqrt(1.5) * 2 * m.elastic.mu;
  const double q = DruckerPragerModel::gammaOf(m.params().frictionAngle) * m.params().cohesion * 1.001;
  Vec3d eps = Vec3d(1, -1, 0) / std::sqrt(2.0) * (q / k);
  DruckerPragerModel::State s;
  ASSERT_TRUE(m.project(eps, s, 1e-3));
  EXPECT_GT(s.plasticStrain, 0.0f);
  EXPECT_LT(m.cohesion(s.plasticStrain), 1e-6 * m.params().cohesion); // cohesion gone
  EXPECT_NEAR(m.frictionAngle(s.plasticStrain), m.params().residualFrictionAngle, 1e-9);
  EXPECT_TRUE(eps.allFinite());
  // At zero pressure the residual, cohesionless material carries no shear.
  EXPECT_NEAR((eps - Vec3d::Constant(eps.sum() / 3)).norm(), 0.0, 1e-12);
}

TEST(DruckerPrager, ChangedParametersTakeEffectInTheConstantStrengthPath) {
  // Review defect: the residual gamma of the fast path was cached at construction and went stale
  // when the parameters changed later. A 30-degree cone yields a state a 40-degree cone carries.
  DruckerPragerModel m = makeModel(30, 30, 0, 0);
  const double p = 1e5, K = m.elastic.bulk(), k = std::sqrt(1.5) * 2 * m.elastic.mu;
  const double q = 1.2 * DruckerPragerModel::gammaOf(30 * M_PI / 180) * p; // 20% beyond the 30-degree cone
  const Vec3d eps = Vec3d::Constant(-p / (3 * K)) + (q / k) * Vec3d(1, -1, 0) / std::sqrt(2.0);
  DruckerPragerModel::State s;
  Vec3d e = eps;
  EXPECT_TRUE(m.project(e, s, 1e-3));
  DruckerPragerParams stronger = m.params();
  stronger.frictionAngle = stronger.residualFrictionAngle = 40 * M_PI / 180;
  m.setParams(stronger);
  e = eps;
  s = {};
  EXPECT_FALSE(m.project(e, s, 1e-3)) << "the 40-degree cone carries it";
}
