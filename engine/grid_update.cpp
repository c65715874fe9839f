#include "engine/grid_update.h"

#include <algorithm>

#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>

namespace talus {

namespace {

/// The contact nodes' velocities under the collider's law, or, where materials with their own
/// basal law have mass, the mass-weighted mean of every law's result.
void applyLaws(const ContactLaw& own, const std::vector<MaterialLaw>& laws, const float* extra, int channels,
               const Vec4* nodes, ContactBatch& batch, const ContactStep& step) {
  // Mass of material law m at contact node i (P2G's extra channel), and its share of the node.
  auto massOf = [&](int i, const MaterialLaw& m) {
    return extra[size_t(batch.node[i]) * size_t(channels) + size_t(m.channel)];
  };
  auto share = [&](int i, const MaterialLaw& m) { return Real(massOf(i, m)) / nodes[batch.node[i]][0]; };
  bool mixed = false;
  for (int i = 0; i < batch.count && !mixed; ++i)
    for (const MaterialLaw& m : laws) mixed |= massOf(i, m) > 0.f;
  if (!mixed) {
    own.apply(batch.contact, batch.count, step);
    return;
  }
  std::copy(batch.contact, batch.contact + batch.count, batch.original);
  own.apply(batch.contact, batch.count, step);
  for (int i = 0; i < batch.count; ++i) {
    Real rest = Real(1);
    for (const MaterialLaw& m : laws) rest -= share(i, m);
    batch.mixed[i] = std::max(rest, Real(0)) * batch.contact[i].v;
  }
  for (const MaterialLaw& m : laws) {
    std::copy(batch.original, batch.original + batch.count, batch.contact);
    for (int i = 0; i < batch.count; ++i) batch.contact[i].params = nullptr; // the region's are the collider law's
    m.law->apply(batch.contact, batch.count, step);
    for (int i = 0; i < batch.count; ++i) batch.mixed[i] += share(i, m) * batch.contact[i].v;
  }
  for (int i = 0; i < batch.count; ++i) batch.contact[i].v = batch.mixed[i];
}

/// Applies one collider to the nodes of block b and returns the impulse it took (momentum removed
/// from the material, N s) and its moment about `ref`.
void applyCollider(const Collider& col, uint32_t b, const BlockCoord& c, double dx, const ContactStep& step,
                   const Vec3d& ref, const FlowColumns::BlockLines* lines, const std::vector<MaterialLaw>& laws,
                   const float* extra, int channels, Vec4* nodes, ContactBatch& batch, double* acc, float* work) {
  col.gather(b, c, dx, nodes, batch);
  if (batch.count == 0 && batch.held == 0) return;
  const bool moving = col.moves();
  // Thickness is measured for every law when any law asks (the grid then has the columns).
  const bool thickness = lines != nullptr;
  for (int i = 0; i < batch.count; ++i) {
    const Vec4& nd = nodes[batch.node[i]];
    ContactNode& cn = batch.contact[i];
    cn.mass = nd[0];
    cn.v = moving ? Vec3(nd.tail<3>() - batch.velocity[i]) : Vec3(nd.tail<3>());
    if (thickness) FlowColumns::at(*lines, batch.node[i], cn.n, Real(dx), cn.h, cn.rho);
  }
  // Erosion's basal work: the tangential impulse the law removed times the sliding speed it left.
  Real slidBefore[kBlockNodes];
  auto tangentialSpeed = [&](int i) { const ContactNode& cn = batch.contact[i]; return (cn.v - cn.v.dot(cn.n) * cn.n).norm(); };
  if (work)
    for (int i = 0; i < batch.count; ++i) slidBefore[i] = tangentialSpeed(i);
  if (laws.empty()) col.law().apply(batch.contact, batch.count, step);
  else applyLaws(col.law(), laws, extra, channels, nodes, batch, step);
  if (work)
    for (int i = 0; i < batch.count; ++i) {
      const Real after = tangentialSpeed(i);
      work[batch.node[i]] = std::max(Real(0), batch.contact[i].mass * (slidBefore[i] - after) * after);
    }
  Vec3d force = Vec3d::Zero(), moment = Vec3d::Zero();
  auto settle = [&](int n, const Vec3& vNew) {
    Vec4& nd = nodes[n];
    const Vec3d impulse = double(nd[0]) * (nd.tail<3>() - vNew).cast<double>();
    const Vec3d x = Vec3d(c.x * kBlockDim + (n >> (2 * kBlockLog2)), c.y * kBlockDim + ((n >> kBlockLog2) & 7),
                          c.z * kBlockDim + (n & 7)) * dx;
    force += impulse;
    moment += (x - ref).cross(impulse);
    nd.tail<3>() = vNew;
  };
  for (int i = 0; i < batch.count; ++i)
    settle(batch.node[i], moving ? Vec3(batch.contact[i].v + batch.velocity[i]) : batch.contact[i].v);
  for (int h = 0; h < batch.held; ++h) {
    const int slot = kBlockNodes - 1 - h;
    settle(batch.node[slot], moving ? batch.velocity[slot] : Vec3(Vec3::Zero()));
  }
  for (int d = 0; d < 3; ++d) acc[d] += force[d], acc[3 + d] += moment[d];
}

} // namespace

void updateGridVelocities(SparseGrid& grid, const GridUpdateParams& prm, const std::vector<Collider*>& colliders,
                          double time, const FlowColumns* columns, std::vector<ColliderLoad>& loads) {
  const Vec3 dtg = prm.dt * prm.gravity;
  const Real keep = Real(1) / (Real(1) + prm.damping * prm.dt);
  const size_t K = colliders.size(), nBlocks = grid.blockCount();
  const double dx = grid.dx;
  const ContactStep step{prm.dt, prm.gravity};
  static const std::vector<MaterialLaw> kNone;
  const std::vector<MaterialLaw>& laws = prm.materialLaws ? *prm.materialLaws : kNone;
  std::vector<Vec3d> refs(K);
  for (size_t k = 0; k < K; ++k) refs[k] = colliders[k]->reference(time);
  // Per block and collider: impulse and its moment (6 doubles), summed in block order below.
  std::vector<double>& perBlock = grid.contactImpulse;
  perBlock.assign(nBlocks * K * 6, 0.0);
  tbb::enumerable_thread_specific<std::unique_ptr<ContactBatch>> batches([] { return std::make_unique<ContactBatch>(); });

  tbb::parallel_for(tbb::blocked_range<size_t>(0, nBlocks, 16), [&](const auto& r) {
    ContactBatch& batch = *batches.local();
    for (size_t b = r.begin(); b != r.end(); ++b) {
      Vec4* nodes = grid.block(uint32_t(b));
      for (int n = 0; n < kBlockNodes; ++n) {
        Vec4& node = nodes[n];
        if (node[0] <= Real(0)) {
          node.tail<3>().setZero();
          continue;
        }
        node.tail<3>() = (node.tail<3>() / node[0] + dtg) * keep;
      }
      const BlockCoord& c = grid.topology.coord(uint32_t(b));
      FlowColumns::BlockLines lines{};
      if (columns) lines = columns->lines(c);
      for (size_t k = 0; k < K; ++k)
        applyCollider(*colliders[k], uint32_t(b), c, dx, step, refs[k], columns ? &lines : nullptr,
                      laws, laws.empty() ? nullptr : grid.blockExtra(uint32_t(b)),
                      grid.channels.count, nodes, batch, &perBlock[(b * K + k) * 6],
                      k == 0 && prm.basalWork ? prm.basalWork + b * kBlockNodes : nullptr);
    }
  });

  loads.assign(K, ColliderLoad{});
  const double invDt = 1.0 / double(prm.dt);
  for (size_t b = 0; b < nBlocks; ++b)
    for (size_t k = 0; k < K && (!prm.counted || (*prm.counted)[b]); ++k) {
      const double* a = &perBlock[(b * K + k) * 6];
      loads[k].force += Vec3d(a[0], a[1], a[2]) * invDt;
      loads[k].moment += Vec3d(a[3], a[4], a[5]) * invDt;
    }
}

} // namespace talus
