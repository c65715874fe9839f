#include "io/output/node_scatter.h"

#include "engine/bspline.h"
#include "engine/padded_block.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <tuple>
#include <tbb/enumerable_thread_specific.h>
#include <tbb/parallel_for.h>
#include <unordered_map>

namespace talus {

namespace {

/// A power of two u with bound / u <= 2^62: a sum of shares of at most `bound` fits an int64.
double unitFor(double bound) {
  if (!(bound > 0) || !std::isfinite(bound)) return 1;
  int e = 0;
  std::frexp(bound, &e); // bound < 2^e
  return std::ldexp(1.0, e - 62);
}

bool coordLess(const BlockCoord& a, const BlockCoord& b) { return std::tie(a.x, a.y, a.z) < std::tie(b.x, b.y, b.z); }

/// The units from every process's exact figures (a count and maxima: no rounding that depends
/// on the ranks): a node's mass of material m is at most the count times m's largest particle
/// mass, its momentum at most the count times the largest mass times the largest velocity component.
std::vector<double> units(Communicator& comm, const Simulation& local) {
  const double n = double(comm.sumOf(local.particleCount()));
  std::vector<double> unit;
  double heaviest = 0, fastest = 0;
  for (const MaterialGroup* g : local.groups()) {
    float m = 0;
    for (const Real p : g->particles.mass) m = std::max(m, float(p));
    for (const Vec3& v : g->particles.v) fastest = std::max(fastest, double(v.cwiseAbs().maxCoeff()));
    const double largest = comm.maxOf(double(m));
    heaviest = std::max(heaviest, largest);
    unit.push_back(unitFor(n * largest));
  }
  fastest = comm.maxOf(fastest);
  unit.push_back(unitFor(n * heaviest * fastest));
  return unit;
}

/// Particles by owning block (the block of their stencil's base node), in particle order.
struct Owners {
  struct Owned {
    int material;
    uint32_t particle;
  };
  std::vector<BlockCoord> blocks;
  std::vector<std::vector<Owned>> particles; ///< per block
};
Owners groupByOwner(const Simulation& local, Real invDx) {
  Owners o;
  std::unordered_map<uint64_t, size_t> index;
  for (int m = 0; m < int(local.groups().size()); ++m) {
    const ParticleSet& P = local.groups()[size_t(m)]->particles;
    for (size_t p = 0; p < P.size(); ++p) {
      const BlockCoord c = owningBlock(P.x[p], invDx);
      const auto [it, fresh] = index.emplace(blockKey(c), o.blocks.size());
      if (fresh) o.blocks.push_back(c), o.particles.emplace_back();
      o.particles[it->second].push_back({m, uint32_t(p)});
    }
  }
  return o;
}

/// Every block the owners' stencils reach, sorted, into `s` with zeroed sums allocated once
/// (grown block by block, the reallocations and their page faults took most of a frame); their
/// indices by key.
std::unordered_map<uint64_t, size_t> allocateReach(NodeSums& s, const std::vector<BlockCoord>& owners) {
  std::unordered_map<uint64_t, size_t> index;
  for (const BlockCoord& c : owners)
    for (int d = 0; d < 8; ++d) {
      const BlockCoord n{c.x + (d >> 2), c.y + ((d >> 1) & 1), c.z + (d & 1)};
      if (index.emplace(blockKey(n), 0).second) s.blocks.push_back(n);
    }
  std::sort(s.blocks.begin(), s.blocks.end(), coordLess);
  for (size_t b = 0; b < s.blocks.size(); ++b) index[blockKey(s.blocks[b])] = b;
  s.values.resize(s.blocks.size() * size_t(s.channels()) * kBlockNodes);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, s.values.size(), size_t(1) << 16),
                    [&](const auto& r) { std::fill(s.values.begin() + ptrdiff_t(r.begin()), s.values.begin() + ptrdiff_t(r.end()), 0); });
  return index;
}

} // namespace

NodeSums scatterNodeSums(Communicator& comm, const Simulation& local) {
  NodeSums s;
  s.dx = local.settings().dx;
  s.materials = int(local.groups().size());
  s.unit = units(comm, local);
  const int channels = s.channels();
  const Real invDx = Real(1.0 / s.dx);
  std::vector<double> inv(s.unit.size());
  for (size_t c = 0; c < inv.size(); ++c) inv[c] = 1.0 / s.unit[c];

  const Owners owners = groupByOwner(local, invDx);
  const std::unordered_map<uint64_t, size_t> index = allocateReach(s, owners.blocks);
  // Rounded to the nearest unit (ties up). Truncation and a correction: the default build's
  // SSE2 has no rounding instruction, and std::floor is a call.
  auto fixed = [&](float v, size_t channel) {
    const double x = double(v) * inv[channel] + 0.5;
    const int64_t t = int64_t(x);
    return double(t) > x ? t - 1 : t;
  };
  // Each owning block's particles into a padded buffer of integer shares, each particle's share
  // rounded on its own (a block's particles may lie on two ranks at a frame: they migrate at the
  // next step), then into the eight blocks it overlaps. Integer sums do not depend on their
  // order, so the owners run on every thread and add atomically, the same bits at any count.
  tbb::enumerable_thread_specific<std::vector<int64_t>> buffers(size_t(kPadNodes) * size_t(channels));
  tbb::parallel_for(size_t(0), owners.blocks.size(), [&](size_t o) {
    std::vector<int64_t>& buf = buffers.local();
    std::fill(buf.begin(), buf.end(), 0);
    const BlockCoord& oc = owners.blocks[o];
    const int origin[3] = {oc.x * kBlockDim, oc.y * kBlockDim, oc.z * kBlockDim};
    for (const Owners::Owned& q : owners.particles[o]) {
      const ParticleSet& P = local.groups()[size_t(q.material)]->particles;
      const QuadraticStencil st(P.x[q.particle] * invDx);
      const float mp = float(P.mass[q.particle]);
      const Vec3 mv = P.mass[q.particle] * P.v[q.particle];
      for (int i = 0; i < 3; ++i)
        for (int j = 0; j < 3; ++j) {
          const float wij = float(st.w[0][i] * st.w[1][j]);
          for (int k = 0; k < 3; ++k) {
            const float w = wij * float(st.w[2][k]);
            int64_t* node = buf.data() + size_t(padIndex(st.base[0] - origin[0] + i, st.base[1] - origin[1] + j,
                                                         st.base[2] - origin[2] + k)) * size_t(channels);
            node[q.material] += fixed(w * mp, size_t(q.material));
            for (int d = 0; d < 3; ++d) node[s.materials + d] += fixed(w * float(mv[d]), size_t(s.materials));
          }
        }
    }
    size_t dest[8];
    for (int d = 0; d < 8; ++d) dest[d] = index.at(blockKey({oc.x + (d >> 2), oc.y + ((d >> 1) & 1), oc.z + (d & 1)}));
    forEachPaddedRow([&](int d, int pad, int node, int n) {
      int64_t* to = s.values.data() + dest[d] * size_t(channels) * kBlockNodes;
      for (int k = 0; k < n; ++k)
        for (int c = 0; c < channels; ++c) {
          const int64_t v = buf[size_t(pad + k) * size_t(channels) + size_t(c)];
          if (v) __atomic_fetch_add(to + size_t(c) * kBlockNodes + size_t(node + k), v, __ATOMIC_RELAXED);
        }
    });
  });
  return s;
}

void gatherNodeSums(Communicator& comm, NodeSums& s) {
  const size_t per = size_t(s.channels()) * kBlockNodes, bytes = per * sizeof(int64_t);
  std::vector<char> mine; // the block count, the coordinates, the values
  if (comm.rank() != 0) {
    const uint64_t n = s.blocks.size();
    mine.resize(sizeof n + n * sizeof(BlockCoord) + s.values.size() * sizeof(int64_t));
    char* p = mine.data();
    std::memcpy(p, &n, sizeof n), p += sizeof n;
    if (n) std::memcpy(p, s.blocks.data(), n * sizeof(BlockCoord)), p += n * sizeof(BlockCoord);
    if (n) std::memcpy(p, s.values.data(), s.values.size() * sizeof(int64_t));
  }
  comm.gatherEach(mine, [](const std::vector<size_t>&) {}, [&](int rank, std::string_view part) {
    if (rank == 0) return; // rank 0's own sums are in place
    uint64_t n = 0;
    if (part.size() < sizeof n) throw std::runtime_error("gatherNodeSums: a part without its block count");
    std::memcpy(&n, part.data(), sizeof n);
    if (part.size() != sizeof n + n * (sizeof(BlockCoord) + bytes))
      throw std::runtime_error("gatherNodeSums: a part that does not hold whole blocks");
    const char* coords = part.data() + sizeof n;
    const char* values = coords + n * sizeof(BlockCoord);
    auto theirs = [&](size_t k) {
      BlockCoord c;
      std::memcpy(&c, coords + k * sizeof c, sizeof c);
      return c;
    };
    // Both lists are sorted (scatterNodeSums): one merge writes each block of the total once (a
    // hash of the blocks, the values grown block by block and a sort after took twice as long).
    std::vector<BlockCoord> blocks;
    std::vector<int64_t> sums;
    blocks.reserve(s.blocks.size() + n);
    sums.reserve((s.blocks.size() + n) * per);
    size_t a = 0, b = 0;
    while (a < s.blocks.size() || b < n) {
      const bool ours = a < s.blocks.size() && (b == n || !coordLess(theirs(b), s.blocks[a]));
      const bool both = ours && b < n && !coordLess(s.blocks[a], theirs(b));
      blocks.push_back(ours ? s.blocks[a] : theirs(b));
      const size_t at = sums.size();
      sums.resize(at + per);
      if (ours) std::copy_n(s.values.begin() + ptrdiff_t(a * per), per, sums.begin() + ptrdiff_t(at));
      else std::memcpy(sums.data() + at, values + b * bytes, bytes);
      if (both)
        for (size_t i = 0; i < per; ++i) {
          int64_t v;
          std::memcpy(&v, values + b * bytes + i * sizeof v, sizeof v);
          sums[at + i] += v;
        }
      a += ours, b += !ours || both;
    }
    s.blocks.swap(blocks), s.values.swap(sums);
  });
}

NodeFields nodeFields(const NodeSums& s) {
  NodeFields f;
  f.dx = s.dx;
  f.materials = s.materials;
  const size_t per = size_t(s.channels()) * kBlockNodes;
  for (size_t b = 0; b < s.blocks.size(); ++b) {
    const int64_t* v = s.values.data() + b * per;
    if (std::none_of(v, v + size_t(s.materials) * kBlockNodes, [](int64_t x) { return x > 0; })) continue;
    f.blocks.push_back(s.blocks[b]);
    for (int m = 0; m < s.materials; ++m)
      for (int n = 0; n < kBlockNodes; ++n) f.mass.push_back(float(double(v[size_t(m) * kBlockNodes + size_t(n)]) * s.unit[size_t(m)]));
    for (int n = 0; n < kBlockNodes; ++n)
      for (int d = 0; d < 3; ++d)
        f.momentum.push_back(float(double(v[size_t(s.materials + d) * kBlockNodes + size_t(n)]) * s.unit[size_t(s.materials)]));
  }
  return f;
}

NodeFields scatterNodeFields(const Simulation& sim) {
  SerialCommunicator one;
  return nodeFields(scatterNodeSums(one, sim));
}

} // namespace talus
