// The step's kernels one at a time, on hand-built particle sets and grids (engine/particle_binning,
// transfer_p2g, transfer_g2p): what each must do whatever the scene.
#include "engine/bspline.h"
#include "engine/contact_laws.h"
#include "engine/grid_update.h"
#include "engine/particle_binning.h"
#include "engine/transfer_g2p.h"
#include "engine/transfer_p2g.h"
#include "materials/elastic.h"
#include "materials/solid_group.h"

#include <gtest/gtest.h>
#include <random>

using namespace talus;

namespace {

constexpr double kDx = 0.1;

/// An elastic group of n particles scattered over a few blocks (some negative coordinates), each
/// tagged by its mass (index + 1) so reorderings can be traced.
std::unique_ptr<SolidGroup<ElasticModel>> scattered(size_t n, unsigned seed) {
  ElasticModel m;
  m.elastic = HenckyElasticity::fromYoung(1e6, 0.3);
  auto g = std::make_unique<SolidGroup<ElasticModel>>("test", 0, 1000.0, m);
  std::mt19937 rng(seed);
  std::uniform_real_distribution<double> u(-1.7, 2.3);
  g->particles.resize(n);
  for (size_t p = 0; p < n; ++p) {
    g->particles.x[p] = Vec3(Real(u(rng)), Real(u(rng)), Real(u(rng)));
    g->particles.v[p] = Vec3(Real(u(rng)), Real(u(rng)), Real(u(rng)));
    g->particles.C[p] = Mat3::Zero();
    g->particles.mass[p] = Real(p + 1);
  }
  g->resizeState(n);
  return g;
}

/// A scattered group binned on a grid of spacing kDx, with the scratch to bin it again.
struct Binned {
  std::unique_ptr<SolidGroup<ElasticModel>> g;
  SparseGrid grid;
  ReorderScratch scratch;
  std::vector<MaterialGroup*> groups;
  Binned(size_t n, unsigned seed) : g(scattered(n, seed)), groups{g.get()} {
    grid.dx = Real(kDx);
    rebin();
  }
  void rebin() { binParticles(groups, grid, scratch); }
};

} // namespace

TEST(Kernels, BinningPartitionsParticlesByOwningBlockAndIsStable) {
  Binned bin(20000, 1);
  auto& g = bin.g;
  const SparseGrid& grid = bin.grid;
  const auto& start = g->blockStart;
  ASSERT_EQ(start.size(), grid.blockCount() + 1);
  EXPECT_EQ(start.front(), 0u);
  EXPECT_EQ(start.back(), g->size());
  std::vector<char> seen(g->size(), 0);
  const Real invDx = Real(1 / kDx);
  for (uint32_t b = 0; b < grid.blockCount(); ++b) {
    ASSERT_LE(start[b], start[b + 1]);
    for (uint32_t p = start[b]; p < start[b + 1]; ++p) {
      EXPECT_EQ(owningBlock(g->particles.x[p], invDx), grid.topology.coord(b)) << "particle " << p;
      // Stable: inside a block the original order (the mass tag) is kept.
      if (p > start[b]) {
        EXPECT_LT(g->particles.mass[p - 1], g->particles.mass[p]);
      }
      const size_t tag = size_t(g->particles.mass[p]) - 1;
      EXPECT_FALSE(seen[tag]);
      seen[tag] = 1;
    }
  }
  // Every owning block has its +1 closure active (P2G writes there) and is listed once.
  size_t owning = 0;
  for (uint32_t b = 0; b < grid.blockCount(); ++b)
    if (start[b + 1] > start[b]) {
      ++owning;
      for (int d = 0; d < 8; ++d) EXPECT_GE(grid.topology.upper(b)[d], 0);
    }
  EXPECT_EQ(owning, grid.owning.size());
  // Binning the binned set again changes nothing (the sorted fast path).
  const auto x = g->particles.x;
  bin.rebin();
  EXPECT_EQ(g->particles.x, x);
}

TEST(Kernels, ReorderMovesOnlyTheRangeWhereParticlesChangedBlockAndCarriesTheirState) {
  Binned bin(20000, 2);
  auto& g = bin.g;
  // A local flow: one particle in the middle moves into the block of a particle 3 000 places on.
  auto& P = g->particles;
  const size_t from = 8000, to = 11000;
  const Real invDx = Real(1 / kDx);
  ASSERT_NE(owningBlock(P.x[from], invDx), owningBlock(P.x[to], invDx));
  P.x[from] = P.x[to];
  for (size_t p = 0; p < g->size(); ++p) g->F[p] = Mat3::Identity() * P.mass[p]; // the state carries the tag too
  const std::vector<Real> before = P.mass;
  bin.rebin();
  // Expected: the stable counting sort of the whole set by block.
  BlockTopology::Lookup lookup(bin.grid.topology);
  std::vector<size_t> order(before.size());
  std::vector<Vec3> x0(before.size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  for (size_t p = 0; p < g->size(); ++p) x0[size_t(P.mass[p]) - 1] = P.x[p]; // positions by tag
  std::stable_sort(order.begin(), order.end(), [&](size_t a, size_t b) {
    return lookup.find(owningBlock(x0[size_t(before[a]) - 1], invDx)) < lookup.find(owningBlock(x0[size_t(before[b]) - 1], invDx));
  });
  size_t first = g->size(), last = 0;
  for (size_t i = 0; i < g->size(); ++i) {
    ASSERT_EQ(P.mass[i], before[order[i]]) << "particle " << i;
    ASSERT_EQ(g->F[i](0, 0), P.mass[i]) << "state of particle " << i;
    if (P.mass[i] != before[i]) first = std::min(first, i), last = i;
  }
  // The copy spans exactly the particles that changed place: between the two, not the whole set.
  EXPECT_EQ(bin.scratch.perm.begin, first);
  EXPECT_EQ(bin.scratch.perm.end, last + 1);
  EXPECT_LT(last + 1 - first, 3100u);
}

TEST(Kernels, P2GWeightsSumToOneAndConserveMassAndMomentum) {
  auto g = scattered(5000, 2);
  std::mt19937 rng(3);
  std::uniform_real_distribution<double> u(-1, 1);
  for (size_t p = 0; p < g->size(); ++p) {
    g->particles.C[p] << Real(u(rng)), Real(u(rng)), Real(u(rng)), Real(u(rng)), Real(u(rng)), Real(u(rng)), Real(u(rng)),
        Real(u(rng)), Real(u(rng));
    g->particles.tau[p] = Sym3{Real(1e3 * u(rng)), Real(1e3 * u(rng)), Real(1e3 * u(rng)), Real(1e3 * u(rng)),
                               Real(1e3 * u(rng)), Real(1e3 * u(rng))};
  }
  SparseGrid grid;
  ReorderScratch scratch;
  grid.dx = Real(kDx);
  std::vector<MaterialGroup*> groups{g.get()};
  binParticles(groups, grid, scratch);
  particlesToGrid(groups, grid, Real(1e-3));
  double gm = 0, pm = 0;
  Vec3d gq = Vec3d::Zero(), pq = Vec3d::Zero();
  for (const Vec4& n : grid.nodes) gm += double(n[0]), gq += n.tail<3>().cast<double>();
  for (size_t p = 0; p < g->size(); ++p)
    pm += double(g->particles.mass[p]), pq += double(g->particles.mass[p]) * g->particles.v[p].cast<double>();
  // Quadratic B-spline weights sum to one and their first moment about the particle vanishes, so
  // neither the affine (APIC) part nor the stress impulse adds net momentum. Float storage: 1e-5.
  EXPECT_NEAR(gm, pm, 1e-6 * pm);
  EXPECT_LT((gq - pq).norm(), 1e-5 * pm);
}

TEST(Kernels, P2GReachesNoPaddedNodeOutsideTheReachedBox) {
  // P2G and G2P clear, add and copy only reachedNodes(b); a node outside it that a particle's
  // stencil touches would lose that particle's mass. Scatter each block over the whole padded
  // neighbourhood and require zeros outside its box, and a box no larger than the stencils'.
  auto g = scattered(5000, 4); // ~40 particles per block: the box path (dense blocks take it all)
  SparseGrid grid;
  ReorderScratch scratch;
  grid.dx = Real(kDx);
  std::vector<MaterialGroup*> groups{g.get()};
  binParticles(groups, grid, scratch);
  std::vector<Vec4> buf(kPadNodes);
  size_t partial = 0;
  for (uint32_t b : grid.owning) {
    const PadBox box = reachedNodes(groups, grid, b);
    scatterBlock(groups, grid, b, Real(1e-3), buf.data(), nullptr);
    int lo[3] = {kPad, kPad, kPad}, hi[3] = {-1, -1, -1};
    for (int i = 0; i < kPad; ++i)
      for (int j = 0; j < kPad; ++j)
        for (int k = 0; k < kPad; ++k) {
          if (buf[size_t(padIndex(i, j, k))][0] == Real(0)) continue;
          const int at[3] = {i, j, k};
          for (int d = 0; d < 3; ++d) lo[d] = std::min(lo[d], at[d]), hi[d] = std::max(hi[d], at[d]);
        }
    for (int d = 0; d < 3; ++d) {
      EXPECT_LE(box.lo[d], lo[d]) << "block " << b << " axis " << d;
      EXPECT_GE(box.hi[d], hi[d]) << "block " << b << " axis " << d;
      // Every stencil node has positive weight, so the mass reaches the box's faces exactly.
      EXPECT_EQ(box.lo[d], lo[d]);
      EXPECT_EQ(box.hi[d], hi[d]);
    }
    partial += (box.hi[0] - box.lo[0] + 1) * (box.hi[1] - box.lo[1] + 1) * (box.hi[2] - box.lo[2] + 1) < kPadNodes;
  }
  EXPECT_GT(partial, grid.owning.size() / 2); // the test exercises partial boxes
}

TEST(Kernels, P2GSpreadsOneParticleWithTheQuadraticWeights) {
  auto g = scattered(1, 4);
  const Vec3 x(Real(0.123), Real(0.456), Real(0.789));
  g->particles.x[0] = x;
  g->particles.mass[0] = 2;
  SparseGrid grid;
  ReorderScratch scratch;
  grid.dx = Real(kDx);
  std::vector<MaterialGroup*> groups{g.get()};
  binParticles(groups, grid, scratch);
  particlesToGrid(groups, grid, Real(1e-3));
  const QuadraticStencil s(x / Real(kDx));
  BlockTopology::Lookup lookup(grid.topology);
  double total = 0;
  for (int i = 0; i < 3; ++i)
    for (int j = 0; j < 3; ++j)
      for (int k = 0; k < 3; ++k) {
        const int I = s.base[0] + i, J = s.base[1] + j, K = s.base[2] + k;
        const int32_t b = lookup.find({I >> kBlockLog2, J >> kBlockLog2, K >> kBlockLog2});
        ASSERT_GE(b, 0);
        const Real m = grid.block(uint32_t(b))[blockNodeIndex(I & 7, J & 7, K & 7)][0];
        EXPECT_NEAR(m, 2 * s.w[0][i] * s.w[1][j] * s.w[2][k], 1e-6);
        total += m;
      }
  EXPECT_NEAR(total, 2, 1e-6);
}

TEST(Kernels, G2PReproducesAnAffineVelocityFieldExactly) {
  // APIC with quadratic B-splines is exact for affine fields: v_p = a + B x_p and C_p = B.
  auto g = scattered(3000, 5);
  SparseGrid grid;
  ReorderScratch scratch;
  grid.dx = Real(kDx);
  std::vector<MaterialGroup*> groups{g.get()};
  binParticles(groups, grid, scratch);
  const Vec3d a(0.3, -0.2, 0.1);
  Mat3d B;
  B << 0.5, -1.0, 0.25, 2.0, 0.1, -0.3, -0.7, 0.4, 0.2;
  for (uint32_t b = 0; b < grid.blockCount(); ++b) {
    const BlockCoord& c = grid.topology.coord(b);
    for (int n = 0; n < kBlockNodes; ++n) {
      const Vec3d xi = kDx * Vec3d(c.x * 8 + (n >> 6), c.y * 8 + ((n >> 3) & 7), c.z * 8 + (n & 7));
      grid.block(b)[n] << 1, (a + B * xi).cast<Real>();
    }
  }
  const auto x0 = g->particles.x;
  gridToParticles(groups, grid, Real(1e-4));
  double vErr = 0, cErr = 0;
  for (size_t p = 0; p < g->size(); ++p) {
    vErr = std::max(vErr, (g->particles.v[p].cast<double>() - (a + B * x0[p].cast<double>())).norm());
    cErr = std::max(cErr, (g->particles.C[p].cast<double>() - B).norm());
    // Advected by dt v.
    EXPECT_NEAR((g->particles.x[p] - x0[p] - Real(1e-4) * g->particles.v[p]).norm(), 0, 1e-6);
  }
  // Float storage of |v| ~ 3 m/s and C ~ 2.5/s summed over 27 nodes: 1e-5 absolute.
  EXPECT_LT(vErr, 1e-5);
  EXPECT_LT(cErr, 1e-4);
}

TEST(Kernels, G2PCountsANonFiniteStressInTheStepThatMadeIt) {
  // Review defect: only velocities were checked, so a NaN stress surfaced a step later (through
  // the next P2G). The gather now checks the stress its update wrote.
  auto g = scattered(10, 6);
  for (size_t p = 0; p < 10; ++p) g->particles.x[p] = Vec3(Real(0.1 + 0.02 * double(p)), Real(0.2), Real(0.3)); // one block
  SparseGrid grid;
  ReorderScratch scratch;
  grid.dx = Real(kDx);
  std::vector<MaterialGroup*> groups{g.get()};
  binParticles(groups, grid, scratch);
  std::vector<Vec4> buf(kPadNodes, Vec4(1, 0, 0, 0));
  const uint32_t b = grid.owning[0];
  const BlockCoord& c = grid.topology.coord(b);
  const G2PBlock blk{buf.data(), {c.x * kBlockDim, c.y * kBlockDim, c.z * kBlockDim}, Real(1e-3), Real(kDx), Real(1 / kDx)};
  G2PStats stats;
  const size_t begin = g->blockStart[b], end = g->blockStart[b + 1];
  ASSERT_GT(end, begin + 1);
  gatherParticles(blk, g->particles, begin, end, stats, [&](size_t p, const Mat3&, double) {
    g->particles.tau[p] = Sym3{};
    if (p == begin + 1) g->particles.tau[p].xz = std::numeric_limits<Real>::quiet_NaN();
  });
  EXPECT_EQ(stats.nonFinite, 1u);
}

TEST(Kernels, GridUpdateMixesMaterialLawsByTheirMassAtANode) {
  // Two materials at one point above a Coulomb (0.2) floor, 3 kg without a law of their own and
  // 1 kg with a sticky one, moving at (1, 0, -0.1): every floor node takes 3/4 of the Coulomb
  // result (1 - 0.2 * 0.1 = 0.98 m/s along x) and 1/4 of the sticky one (at rest).
  auto a = scattered(1, 5), b = scattered(1, 6);
  b->basalLaw = makeContactLaw(StickyLaw{});
  for (auto* g : {a.get(), b.get()}) {
    g->particles.x[0] = Vec3(Real(0.33), Real(0.34), Real(0.02));
    g->particles.v[0] = Vec3(1, 0, Real(-0.1));
  }
  a->particles.mass[0] = 3, b->particles.mass[0] = 1;
  SparseGrid grid;
  ReorderScratch scratch;
  grid.dx = Real(kDx);
  grid.channels.count = 1;
  grid.channels.scatterOf = {{}, {{0, 1.f}}}; // channel 0: the sticky material's node mass
  std::vector<MaterialGroup*> groups{a.get(), b.get()};
  binParticles(groups, grid, scratch);
  particlesToGrid(groups, grid, Real(1e-3));
  Collider floor = Collider::face("z_min", 2, false, 0.0, makeContactLaw(CoulombLaw{Real(0.2)}));
  floor.prepare(grid.topology, kDx, 0.0);
  GridUpdateParams prm;
  prm.dt = Real(1e-3);
  const std::vector<MaterialLaw> laws{{0, b->basalLaw.get()}};
  prm.materialLaws = &laws;
  std::vector<ColliderLoad> loads;
  updateGridVelocities(grid, prm, {&floor}, 0.0, nullptr, loads);
  int onFloor = 0, above = 0;
  for (uint32_t blk = 0; blk < grid.blockCount(); ++blk)
    for (int n = 0; n < kBlockNodes; ++n) {
      const Vec4& nd = grid.block(blk)[n];
      if (nd[0] <= 0) continue;
      const int k = grid.topology.coord(blk).z * kBlockDim + (n & 7);
      if (k <= 0) {
        ++onFloor;
        EXPECT_NEAR(nd[1], 0.75 * 0.98, 1e-6) << "floor node";
        EXPECT_NEAR(nd[3], 0, 1e-7);
      } else {
        ++above;
        EXPECT_NEAR(nd[1], 1, 1e-6);
      }
    }
  EXPECT_EQ(onFloor, 18); // the stencil spans node layers k = -1, 0 (in the floor) and 1
  EXPECT_EQ(above, 9);
}
