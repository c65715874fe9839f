// Every case of every contact law (engine/contact_laws.h), one node at a time: the laws are the
// whole of what a collider does to the material, so each branch is pinned here exactly.
#include "engine/contact_laws.h"

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
