// Modified Cam Clay return mapping and hardening, tested alone (physics.md 4.2).
#include "materials/cam_clay.h"

#include <gtest/gtest.h>
#include <random>

using namespace talus;

namespace {
CamClayModel snow() {
  CamClayModel m;
  m.elastic = HenckyElasticity::fromYoung(3e6, 0.3);
  m.params = CamClayParams{1.2, 0.4, 175e3, 0.4, 0.1};
  return m;
}
double pOf(const CamClayModel& m, const Vec3d& e) { return -m.elastic.bulk() * e.sum(); }
double qOf(const CamClayModel& m, const Vec3d& e) {
  return std::sqrt(1.5) * 2 * m.elastic.mu * (e - Vec3d::Constant(e.sum() / 3)).norm();
}
} // namespace

TEST(CamClay, HardeningFollowsEquationTen) {
  const auto m = snow();
  const double K = m.elastic.bulk();
  EXPECT_NEAR(m.preconsolidation(m.initialVolumetricStrain()), 175e3, 1e-6);
  for (double ev : {-2.0, -1.0, -0.5, -0.1, 0.0, 0.3})
    EXPECT_NEAR(m.preconsolidation(ev), K * std::sinh(0.1 * std::max(-ev, 0.0)), 1e-9 * K);
}

TEST(CamClay, TheStateKeepsItsFlagInEpsVsLastBitWithinOneUlp) {
  // 4 bytes a particle's state (issue 36): the flag read back as set, eps_v within one float ulp.
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(-1, 1);
  for (int t = 0; t < 10000; ++t) {
    const double ev = unit(rng) * std::pow(10.0, -6 * std::abs(unit(rng)));
    const bool flag = t % 3 == 0;
    CamClayModel::State s;
    s.set(ev, flag);
    EXPECT_EQ(s.yielded(), flag);
    const float f = float(ev);
    EXPECT_LE(std::abs(double(s.volumetricPlasticStrain()) - ev), std::abs(std::nextafter(f, 2.0f * f) - f) * 1.5);
    s.set(s.volumetricPlasticStrain(), flag); // stored values are fixed points
    EXPECT_EQ(s.yielded(), flag);
  }
  CamClayModel::State zero;
  EXPECT_FALSE(zero.yielded());
  EXPECT_EQ(zero.volumetricPlasticStrain(), 0.0f);
  static_assert(sizeof(CamClayModel::State) == 4, "128 bytes a particle");
}

TEST(CamClay, ReturnLandsOnTheSurfaceKeepsAdmissibleStatesAndIsIdempotent) {
  const auto m = snow();
  std::mt19937 rng(11);
  std::uniform_real_distribution<double> strain(-0.3, 0.3), unit(0, 1);
  int plastic = 0, admissible = 0, compacted = 0, dilated = 0;
  for (int t = 0; t < 40000; ++t) {
    Vec3d eps(strain(rng), strain(rng), strain(rng));
    eps *= std::pow(10.0, -2 * unit(rng));
    CamClayModel::State s;
    s.set(m.initialVolumetricStrain() * (0.2 + 1.6 * unit(rng)), unit(rng) < 0.5);
    const Vec3d trial = eps;
    const auto s0 = s;
    const double p0 = m.preconsolidation(s0.volumetricPlasticStrain());
    const double scale = (1 + 2 * m.params.beta) * std::pow(qOf(m, trial), 2) +
                         m.params.M * m.params.M * std::pow(std::abs(pOf(m, trial)) + p0, 2);
    if (!m.project(eps, s, 1e-3)) {
      EXPECT_LE(m.yield(trial, s0), 0.0);
      EXPECT_EQ(eps, trial);
      ++admissible;
      continue;
    }
    ++plastic;
    EXPECT_TRUE(s.yielded());
    EXPECT_LE(std::abs(m.yield(eps, s)), 1e-6 * scale);
    // Compaction (trial beyond the cap) hardens, dilation softens; by one float ulp at most the
    // other way, which the yield flag in eps_v's last bit may cost (State).
    const float ev = s.volumetricPlasticStrain(), ev0 = s0.volumetricPlasticStrain();
    if (pOf(m, eps) < pOf(m, trial) - 1e-9 * p0) {
      EXPECT_LE(ev, std::nextafter(ev0, 1.0f));
      ++compacted;
    } else if (pOf(m, eps) > pOf(m, trial) + 1e-9 * p0) {
      EXPECT_GE(ev, std::nextafter(ev0, -1.0f));
      EXPECT_LE(m.preconsolidation(s.volumetricPlasticStrain()), p0 * (1 + 1e-6));
      ++dilated;
    }
    // Associative, closest point in the energy norm: a second projection changes nothing.
    Vec3d again = eps;
    auto s2 = s;
    m.project(again, s2, 1e-3);
    EXPECT_LE((again - eps).norm(), 1e-6 * (trial.norm() + 1e-9));
  }
  EXPECT_GT(plastic, 5000);
  EXPECT_GT(admissible, 5000);
  EXPECT_GT(compacted, 500);
  EXPECT_GT(dilated, 500);
}

TEST(CamClay, SlopeDropsToFlowingValueAfterFirstYield) {
  const auto m = snow();
  // Pure shear at p = p0/2 (the ellipse's widest point for beta = 0): admissible for M = 1.2
  // if q < M p0 ... choose q between the M_s and M surfaces.
  CamClayModel::State s;
  s.set(m.initialVolumetricStrain(), false);
  const double p0 = m.preconsolidation(s.volumetricPlasticStrain());
  const double centre = 0.5 * (1 - m.params.beta) * p0, ap = 0.5 * (1 + m.params.beta) * p0;
  const double qMax = m.params.M * ap / std::sqrt(1 + 2 * m.params.beta);
  const double K = m.elastic.bulk(), k = std::sqrt(1.5) * 2 * m.elastic.mu;
  Vec3d eps = Vec3d::Constant(-centre / (3 * K)) + Vec3d(1, -1, 0) / std::sqrt(2.0) * (0.8 * qMax / k);
  EXPECT_FALSE(m.project(eps, s, 1e-3)); // intact snow carries it
  CamClayModel::State yielded = s;
  yielded.set(yielded.volumetricPlasticStrain(), true);
  EXPECT_TRUE(m.project(eps, yielded, 1e-3)); // flowing snow (M_s = 0.4) does not
  EXPECT_LT(qOf(m, eps), 0.4 / 1.2 * qMax * 1.01);
}

// The projection's sensitivity to the ellipse size, dp/dp0 and dq/dp0, is analytic (the Newton
// hardening solve's derivative). Central differences with a 1e-6 relative step are accurate to
// ~1e-9 here; 1e-5 leaves room and still catches a wrong sign or a missing curvature term
// (those are O(1) errors).
TEST(CamClay, ProjectionSensitivityToTheEllipseSizeMatchesFiniteDifferences) {
  const auto m = snow();
  const CamClayModel::Scales scales(m);
  std::mt19937 rng(5);
  std::uniform_real_distribution<double> unit(0, 1);
  int outside = 0;
  for (int t = 0; t < 2000; ++t) {
    const double p0 = 1e3 * std::pow(10.0, 3 * unit(rng));
    const double pTr = p0 * (-2 + 5 * unit(rng)), qTr = p0 * 3 * unit(rng);
    double p, q, dp, dq, pPlus, qPlus, pMinus, qMinus, unused1, unused2, tRoot = 0;
    m.projectOntoEllipse(scales, pTr, qTr, p0, p, q, dp, dq, tRoot);
    if (p == pTr && q == qTr) continue; // inside: P = z, no sensitivity
    ++outside;
    const double h = 1e-6 * p0;
    // Started from this root (the hardening solve's warm start): on both sides of it.
    double tPlus = tRoot, tMinus = tRoot;
    m.projectOntoEllipse(scales, pTr, qTr, p0 + h, pPlus, qPlus, unused1, unused2, tPlus);
    m.projectOntoEllipse(scales, pTr, qTr, p0 - h, pMinus, qMinus, unused1, unused2, tMinus);
    EXPECT_NEAR(dp, (pPlus - pMinus) / (2 * h), 1e-5 * (1 + std::abs(dp))) << pTr << " " << qTr << " " << p0;
    EXPECT_NEAR(dq, (qPlus - qMinus) / (2 * h), 1e-5 * (1 + std::abs(dq))) << pTr << " " << qTr << " " << p0;
  }
  EXPECT_GT(outside, 1000);
}

// The return's inner solve: the closest point on an axis-aligned ellipse to an outside point, against
// bisection of its root equation to the last bit, for ellipses of aspect 1e-3..1e3 and points from
// just outside to 1e4 semi-axes away (loose snow: p0 -> 0 shrinks the ellipse under a fixed trial
// state). Cold starts and warm ones (the previous root of a 1 % larger ellipse, as the hardening
// solve gives). Agreement to 1e-12 of the distance scale (the bisection's root is exact to the last
// bits; 1e-12 leaves room for the closed form's rounding). The step counts bound the cost: Newton on
// S itself took 2.06 cold (at most 23) and 2.55 warm on these points, this one 1.42 (10) and 1.69.
TEST(CamClay, ClosestPointOnTheEllipseMatchesBisectionInFewNewtonSteps) {
  std::mt19937 rng(23);
  std::uniform_real_distribution<double> unit(0, 1);
  int cases = 0, steps = 0, most = 0, warmSteps = 0, warmMost = 0;
  for (int k = 0; k < 20000; ++k) {
    const double A = 1, B = std::pow(10.0, -3 + 6 * unit(rng));
    const double far = std::pow(10.0, 4 * unit(rng)), phi = 0.5 * M_PI * unit(rng);
    const double x = A * (1 + far) * std::cos(phi) + 1e-3, y = B * (1 + far) * std::sin(phi) + 1e-3 * B;
    auto S = [&](double t) { return std::pow(A * x / (t + A * A), 2) + std::pow(B * y / (t + B * B), 2); };
    double lo = 0, hi = 1;
    while (S(hi) > 1) hi *= 2;
    for (int i = 0; i < 200; ++i) (S(0.5 * (lo + hi)) > 1 ? lo : hi) = 0.5 * (lo + hi);
    const double tRef = 0.5 * (lo + hi);
    const double pxRef = A * A * x / (tRef + A * A), pyRef = B * B * y / (tRef + B * B);
    const double scale = std::hypot(x, y);
    double px, py, t = 0;
    int n = 0;
    CamClayModel::closestOnEllipse(x, y, A, B, px, py, t, &n);
    EXPECT_NEAR(px, pxRef, 1e-12 * scale) << x << " " << y << " " << B;
    EXPECT_NEAR(py, pyRef, 1e-12 * scale) << x << " " << y << " " << B;
    ++cases, steps += n, most = std::max(most, n);
    // Warm: the root of the same point and a 1 % larger ellipse as the guess.
    double qx, qy, t1 = 0, unusedX, unusedY;
    CamClayModel::closestOnEllipse(x, y, 1.01 * A, 1.01 * B, unusedX, unusedY, t1);
    CamClayModel::closestOnEllipse(x, y, A, B, qx, qy, t1, &n);
    EXPECT_NEAR(qx, pxRef, 1e-12 * scale);
    EXPECT_NEAR(qy, pyRef, 1e-12 * scale);
    warmSteps += n, warmMost = std::max(warmMost, n);
  }
  EXPECT_LE(double(steps) / cases, 1.8);
  EXPECT_LE(double(warmSteps) / cases, 2.0);
  EXPECT_LE(most, 12);
  std::printf("closest point: %.2f Newton steps cold (at most %d), %.2f warm (at most %d)\n", double(steps) / cases,
              most, double(warmSteps) / cases, warmMost);
}

// Newton on the hardening equation lands where the bracketed (Illinois) solve does, to 1e-9 in
// eps_v (the state is stored in float, 6e-8 relative) and 1e-8 of the stress scale in (p, q),
// in at most six projections and three or fewer on average (the bracketed solve takes ~6).
TEST(CamClay, NewtonHardeningAgreesWithTheBracketedSolveInFewProjections) {
  const auto m = snow();
  const double K = m.elastic.bulk();
  std::mt19937 rng(17);
  std::uniform_real_distribution<double> strain(-0.3, 0.3), unit(0, 1);
  int solved = 0, projections = 0, most = 0;
  for (int t = 0; t < 20000; ++t) {
    Vec3d eps(strain(rng), strain(rng), strain(rng));
    eps *= std::pow(10.0, -1 - 3 * unit(rng));
    CamClayModel::State s;
    s.set(m.initialVolumetricStrain() * std::pow(10.0, -4 * unit(rng)), true);
    const double pTr = pOf(m, eps), qTr = qOf(m, eps);
    const double ev0 = s.volumetricPlasticStrain(), p00 = m.preconsolidation(ev0);
    if (m.yield(pTr, qTr, p00, m.params.Ms) <= 0) continue;
    double evN, pN, qN, evB, pB, qB;
    int n = 0;
    ASSERT_TRUE(m.hardenNewton(pTr, qTr, ev0, p00, evN, pN, qN, &n)) << pTr << " " << qTr << " " << ev0;
    m.hardenBracketed(pTr, qTr, ev0, p00, evB, pB, qB);
    const double scale = std::abs(pTr) + qTr + p00;
    EXPECT_NEAR(evN, evB, 1e-9 * (1 + std::abs(evB)));
    EXPECT_NEAR(pN, pB, 1e-8 * scale);
    EXPECT_NEAR(qN, qB, 1e-8 * scale);
    // Consistency: the plastic volume change is the pressure's return, G = 0.
    EXPECT_NEAR(evN - ev0, (pN - pTr) / K, 1e-9 * (1 + std::abs(evN)) + 1e-8 * scale / K);
    ++solved, projections += n, most = std::max(most, n);
  }
  EXPECT_GT(solved, 5000);
  EXPECT_LE(most, 6);
  EXPECT_LE(double(projections) / solved, 3.0);
  std::printf("Newton hardening: %d solves, %.2f projections on average, at most %d\n", solved,
              double(projections) / solved, most);
}
