// P2G's and G2P's stencil rows in SIMD lanes (engine/stencil_lanes.h) against the scalar loops,
// on random particles and nodes, on every Highway target this machine runs.
#include "engine/bspline.h"
#include "engine/padded_block.h"
#include "engine/stencil_lanes.h"
#include "engine/transfer_g2p.h"
#include "simd_targets.h"

#include <gtest/gtest.h>

#include <cstring>
#include <random>
#include <vector>

// The kernels work on float nodes; the double-precision build keeps the scalar loops.
#ifndef TALUS_DOUBLE
namespace talus {
namespace {

constexpr Real kDx = 0.1f;

/// A padded buffer of random nodes (mass in (0, 1), velocities up to 5 m/s) and a chunk of random
/// particles of the block at the origin (stencils inside the buffer).
struct RandomBlock {
  std::vector<Vec4> nodes = std::vector<Vec4>(kPadNodes);
  QuadraticStencil st[kGatherChunk];
  explicit RandomBlock(unsigned seed) {
    std::mt19937 rng(seed);
    std::uniform_real_distribution<float> u(0, 1);
    for (Vec4& n : nodes) n << u(rng), 10 * u(rng) - 5, 10 * u(rng) - 5, 10 * u(rng) - 5;
    for (auto& s : st) s = QuadraticStencil(Vec3(0.5f + 8 * u(rng), 0.5f + 8 * u(rng), 0.5f + 8 * u(rng)));
  }
  StencilRows rows() const {
    StencilRows r;
    for (int k = 0; k < kGatherChunk; ++k) {
      r.first[k] = padIndex(st[k].base[0], st[k].base[1], st[k].base[2]);
      std::memcpy(r.w[k], st[k].w, sizeof r.w[k]);
    }
    return r;
  }
};

TEST(StencilLanes, GatherAgreesWithTheScalarGatherToFloatRounding) {
  // The two sum the same 27 terms per channel in another order: each differs from the exact sum
  // by at most ~27 float roundings of the largest term, 27 x 2^-24 x 5 m/s = 8e-6 m/s. C's columns
  // are 4/dx (b - f v), b's sums (weights up to 2) and f v (f up to 1.5) each carrying that
  // error: 4/dx x (2 + 1.5) x 8e-6 = 1.1e-3 1/s at dx 0.1 m.
  const int origin[3] = {0, 0, 0};
  double worstV = 0, worstC = 0;
  for (unsigned seed = 1; seed <= 200; ++seed) {
    const RandomBlock b(seed);
    Vec3 vel[kGatherChunk];
    Mat3 C[kGatherChunk];
    gatherChunkVelocities(b.nodes.data(), origin, b.st, kGatherChunk, 1 / kDx, vel, C);
    for (int k = 0; k < kGatherChunk; ++k) {
      Vec3 v;
      Mat3 c;
      gatherVelocity(b.nodes.data(), b.st[k], b.st[k].base[0], b.st[k].base[1], b.st[k].base[2], 1 / kDx, v, c);
      worstV = std::max(worstV, double((vel[k] - v).cwiseAbs().maxCoeff()));
      worstC = std::max(worstC, double((C[k] - c).cwiseAbs().maxCoeff()));
    }
  }
  std::printf("largest difference: velocity %.3g m/s, C %.3g 1/s\n", worstV, worstC);
  EXPECT_LT(worstV, 8e-6);
  EXPECT_LT(worstC, 4 / kDx * 3.5 * 8e-6);
  EXPECT_GT(worstV, 0) << "the orders differ: a zero difference would mean the test compares a path with itself";
}

TEST(StencilLanes, ScatterAddsWhatTheScalarScatterAddsBitForBitInParticleOrder) {
  // The kernel forms (w_i w_j) w_k (((q0 + i a0) + j a1) + k a2) as the scalar P2G did; the 16
  // particles share nodes, so the sums also hold the order of the particles.
  for (unsigned seed = 1; seed <= 50; ++seed) {
    const RandomBlock b(seed);
    std::mt19937 rng(seed + 1000);
    std::uniform_real_distribution<float> u(-1, 1);
    ScatteredRows q{};
    std::vector<Vec4> ref(kPadNodes, Vec4::Zero()), got(kPadNodes, Vec4::Zero());
    for (int p = 0; p < kGatherChunk; ++p) {
      Vec4 q0, a0, a1, a2;
      q0 << 1 + u(rng), u(rng), u(rng), u(rng);
      a0 << 0, u(rng), u(rng), u(rng);
      a1 << 0, u(rng), u(rng), u(rng);
      a2 << 0, u(rng), u(rng), u(rng);
      std::memcpy(q.q0[p], q0.data(), 16);
      std::memcpy(q.a0[p], a0.data(), 16);
      std::memcpy(q.a1[p], a1.data(), 16);
      std::memcpy(q.a2[p], a2.data(), 16);
      const QuadraticStencil& s = b.st[p];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const Vec4 qij = (q0 + Real(i) * a0) + Real(j) * a1;
          const Real wij = s.w[0][i] * s.w[1][j];
          Vec4* row = ref.data() + padIndex(s.base[0] + i, s.base[1] + j, s.base[2]);
          row[0] += (wij * s.w[2][0]) * qij;
          row[1] += (wij * s.w[2][1]) * (qij + a2);
          row[2] += (wij * s.w[2][2]) * (qij + Real(2) * a2);
        }
    }
    scatterRows(got[0].data(), b.rows(), q, kGatherChunk);
    for (int n = 0; n < kPadNodes; ++n) ASSERT_TRUE(got[n] == ref[n]) << "node " << n << ", seed " << seed;
  }
}

TEST(StencilLanes, EveryTargetGathersAndScattersTheSameBits) {
  const RandomBlock b(7);
  const StencilRows rows = b.rows();
  ScatteredRows q{};
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1, 1);
  for (int p = 0; p < kGatherChunk; ++p)
    for (int c = 0; c < 4; ++c) q.q0[p][c] = u(rng), q.a0[p][c] = u(rng), q.a1[p][c] = u(rng), q.a2[p][c] = u(rng);
  GatheredRows bestGather;
  gatherRows(b.nodes[0].data(), rows, kGatherChunk, bestGather);
  std::vector<Vec4> bestScatter = b.nodes;
  scatterRows(bestScatter[0].data(), rows, q, kGatherChunk);
  forEachSimdTarget([&] {
    GatheredRows g;
    gatherRows(b.nodes[0].data(), rows, kGatherChunk, g);
    for (int p = 0; p < kGatherChunk; ++p) {
      EXPECT_EQ(std::memcmp(g.all[p], bestGather.all[p], 48), 0) << "particle " << p;
      EXPECT_EQ(std::memcmp(g.alongI[p], bestGather.alongI[p], 48), 0) << "particle " << p;
      EXPECT_EQ(std::memcmp(g.alongJ[p], bestGather.alongJ[p], 48), 0) << "particle " << p;
    }
    std::vector<Vec4> s = b.nodes;
    scatterRows(s[0].data(), rows, q, kGatherChunk);
    EXPECT_EQ(std::memcmp(s.data(), bestScatter.data(), s.size() * sizeof(Vec4)), 0);
  });
}

} // namespace
} // namespace talus
#endif
