// Every case of every contact law (engine/contact_laws.h), one node at a time: the laws are the
// whole of what a collider does to the material, so each branch is pinned here exactly.
#include "engine/contact_laws.h"
#include "engine/samosat_law.h"
#include "engine/voellmy_law.h"

#include <gtest/gtest.h>

using namespace talus;

namespace {

ContactNode node(const Vec3& v, const Vec3& n = Vec3(0, 0, 1)) { return ContactNode{v, n, Real(1)}; }

template <class Law> Vec3 apply(const Law& law, const Vec3& v, const Vec3& n = Vec3(0, 0, 1)) {
  ContactNode c = node(v, n);
  ContactLawOf<Law>(law).apply(&c, 1, ContactStep{Real(1e-3)});
  return c.v;
}

} // namespace

TEST(ContactLaws, StickyHoldsEveryNodeWhateverItsMotion) {
  EXPECT_EQ(apply(StickyLaw{}, Vec3(1, 2, -3)), Vec3::Zero());
  EXPECT_EQ(apply(StickyLaw{}, Vec3(1, 2, 3)), Vec3::Zero()); // separating too: no-slip glues
}

TEST(ContactLaws, SlipRemovesOnlyTheApproachingNormalVelocity) {
  EXPECT_EQ(apply(SlipLaw{}, Vec3(1, 2, -3)), Vec3(1, 2, 0));
  EXPECT_EQ(apply(SlipLaw{}, Vec3(1, 2, 3)), Vec3(1, 2, 3)); // separating: untouched
  // On an inclined normal the tangential part is kept exactly.
  const Vec3 n = Vec3(1, 0, 1).normalized(), v(0, 0, -2);
  const Vec3 out = apply(SlipLaw{}, v, n);
  EXPECT_NEAR(out.dot(n), 0, 1e-6);
  EXPECT_NEAR((out - (v - v.dot(n) * n)).norm(), 0, 1e-6);
}

TEST(ContactLaws, CoulombSlidesWithTheTangentialSpeedReducedByMuTimesTheNormal) {
  const CoulombLaw law{Real(0.5)};
  // |vt| = 4 > mu |vn| = 1: sliding, |vt| -> 4 - 1 = 3 along the same direction.
  const Vec3 out = apply(law, Vec3(4, 0, -2));
  EXPECT_NEAR(out.x(), 3, 1e-6);
  EXPECT_NEAR(out.y(), 0, 1e-6);
  EXPECT_NEAR(out.z(), 0, 1e-6);
}

TEST(ContactLaws, CoulombStaticFrictionHoldsBelowTheCone) {
  const CoulombLaw law{Real(0.5)};
  EXPECT_EQ(apply(law, Vec3(0.9, 0, -2)), Vec3::Zero()); // |vt| 0.9 <= mu |vn| = 1
  EXPECT_EQ(apply(law, Vec3(1, 0, -2)), Vec3::Zero());   // on the cone: held
}

TEST(ContactLaws, CoulombLeavesASeparatingNodeAlone) {
  const CoulombLaw law{Real(0.5)};
  EXPECT_EQ(apply(law, Vec3(4, 1, 2)), Vec3(4, 1, 2));
  EXPECT_EQ(apply(law, Vec3(4, 1, 0)), Vec3(4, 1, 0)); // tangential motion on the surface: free
}

TEST(ContactLaws, CoulombWithZeroFrictionIsSlip) {
  const Vec3 v(3, -1, -2);
  EXPECT_EQ(apply(CoulombLaw{Real(0)}, v), apply(SlipLaw{}, v));
}

TEST(ContactLaws, ABatchAppliesTheLawToEveryNode) {
  ContactNode nodes[3] = {node(Vec3(1, 0, -1)), node(Vec3(0, 1, 1)), node(Vec3(0, 0, -5))};
  ContactLawOf<SlipLaw>(SlipLaw{}).apply(nodes, 3, ContactStep{});
  EXPECT_EQ(nodes[0].v, Vec3(1, 0, 0));
  EXPECT_EQ(nodes[1].v, Vec3(0, 1, 1));
  EXPECT_EQ(nodes[2].v, Vec3::Zero());
}

namespace {

/// The law's node update for a node moving at ut along x while dvn of normal velocity is removed,
/// on a horizontal surface under gravity 9.81 with flow thickness h and density rho.
template <class Law> double slide(const Law& law, double ut, double dvn, double h, double rho = 200) {
  ContactNode c{Vec3(Real(ut), 0, Real(-dvn)), Vec3(0, 0, 1), Real(1)};
  c.h = Real(h), c.rho = Real(rho);
  law.apply(c, ContactStep{Real(1e-3), Vec3(0, 0, Real(-9.81))});
  EXPECT_NEAR(c.v.y(), 0, 1e-9);
  EXPECT_NEAR(c.v.z(), 0, 1e-9); // normal approach removed
  EXPECT_GE(c.v.x(), 0);         // never reversed
  return c.v.x();
}

/// AvaFrame's SamosATfric (com1DFA/DFAToolsCython.pyx) with its default parameters, written out
/// independently of engine/samosat_law.h: tau (Pa) for density, speed, normal stress, thickness.
double avaframeSamosAt(double rho, double v, double p, double h, double mu = 0.155) {
  const double tau0 = 0, Rs0 = 0.222, kappa = 0.43, R = 0.05, B = 4.13;
  const double Rs = rho * v * v / (p + 0.001);
  double div = h / R;
  if (div < 1.0) div = 1.0;
  div = std::log(div) / kappa + B;
  return tau0 + p * mu * (1.0 + Rs0 / (Rs0 + Rs)) + rho * v * v / (div * div);
}

} // namespace

TEST(ContactLaws, VoellmyStepIsTheImplicitRootOfItsDrag) {
  const VoellmyLaw law{Real(0.2), Real(1000)};
  const double ut = 10, dvn = 0.01, h = 2;
  const double u = slide(law, ut, dvn, h);
  // u = ut - mu dvn - g dvn u^2 / (xi g_n h), g_n = g here: the root of the implicit step.
  // Tolerance: the velocity is stored in float (Real), so a few float ulps of ut.
  EXPECT_NEAR(u, ut - 0.2 * dvn - dvn * u * u / (1000 * h), 1e-6 * ut);
  EXPECT_LT(u, ut - 0.2 * dvn);
  // Below the Coulomb part it sticks; a thicker flow feels less drag.
  EXPECT_EQ(slide(law, 0.001, dvn, h), 0);
  EXPECT_GT(slide(law, ut, dvn, 4 * h), u);
}

TEST(ContactLaws, VoellmyOnAWallKeepsOnlyItsCoulombPart) {
  // No gravity into a vertical wall: no hydrostatic normal stress, so no turbulent drag.
  const VoellmyLaw law{Real(0.2), Real(1000)};
  // The wall's normal points to -x (into the flow); the flow presses into it at 0.5 m/s and
  // slides down at 5.
  ContactNode c{Vec3(Real(0.5), 0, Real(-5)), Vec3(-1, 0, 0), Real(1)};
  c.h = 1, c.rho = 300;
  law.apply(c, ContactStep{Real(1e-3), Vec3(0, 0, Real(-9.81))});
  EXPECT_NEAR(c.v.z(), -(5 - 0.2 * 0.5), 1e-6);
  EXPECT_NEAR(c.v.x(), 0, 1e-7);
}

TEST(ContactLaws, SamosAtShearIsAvaFramesFormula) {
  // tau / sigma against AvaFrame's own function at speeds from rest to 60 m/s, thicknesses
  // below the roughness clamp to 5 m: the same law, to round-off.
  const double p[6] = {0.155, 0, 0.222, 0.43, 0.05, 4.13};
  for (double h : {0.01, 0.3, 1.0, 5.0})
    for (double v : {0.0, 0.5, 5.0, 20.0, 60.0}) {
      const double rho = 200, sigma = rho * 9.81 * h;
      EXPECT_NEAR(SamosAtLaw::shearOverNormal(v, sigma, rho, h, p) * sigma, avaframeSamosAt(rho, v, sigma, h),
                  1e-9 * avaframeSamosAt(rho, v, sigma, h))
          << "h " << h << " v " << v;
    }
}

// The implicit step's Newton uses the shear's analytic slope; central differences with a 1e-5
// relative step are accurate to ~1e-9 of the slope here, so 1e-6 catches a wrong term (O(1)).
TEST(ContactLaws, SamosAtShearSlopeMatchesFiniteDifferences) {
  const double p[6] = {0.155, 0, 0.222, 0.43, 0.05, 4.13};
  for (double h : {0.01, 0.3, 1.0, 5.0})
    for (double v : {0.01, 0.5, 5.0, 20.0, 60.0}) {
      const double rho = 200, sigma = rho * 9.81 * h, e = 1e-5 * v;
      const SamosAtLaw::Shear shear(sigma, rho, h, p);
      const double fd = (shear(v + e) - shear(v - e)) / (2 * e);
      EXPECT_NEAR(shear.slope(v), fd, 1e-6 * (std::abs(fd) + 1e-3)) << "h " << h << " v " << v;
    }
}

TEST(ContactLaws, SamosAtStepSolvesTheImplicitBalanceAndHoldsTwiceMuAtRest) {
  const SamosAtLaw law;
  const double dvn = 0.01, h = 1, rho = 200, sigma = rho * 9.81 * h;
  const double ut = 12;
  const double u = slide(law, ut, dvn, h, rho);
  EXPECT_NEAR(u, ut - dvn * avaframeSamosAt(rho, u, sigma, h) / sigma, 1e-7 * ut);
  // At rest the Coulomb part is 2 mu: a node just below 2 mu dvn sticks, one above slides.
  EXPECT_EQ(slide(law, 0.99 * 2 * 0.155 * dvn, dvn, h, rho), 0);
  EXPECT_GT(slide(law, 1.01 * 2 * 0.155 * dvn, dvn, h, rho), 0);
}

TEST(ContactLaws, RegionParametersReplaceTheLawsOwn) {
  const CoulombLaw law{Real(0.1)};
  const float mu = 0.5f;
  ContactNode c{Vec3(Real(0.9), 0, Real(-2)), Vec3(0, 0, 1), Real(1)};
  c.params = &mu;
  law.apply(c, ContactStep{});
  EXPECT_EQ(c.v, Vec3::Zero()); // 0.9 <= 0.5 * 2: held by the region's friction, not 0.1
}
