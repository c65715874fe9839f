#include "engine/flow_thickness.h"

#include <algorithm>
#include <cmath>

#include <tbb/parallel_for.h>

namespace talus {

namespace {
/// Node n of a block: its index along `axis` and the line index (the other two, 0..63).
inline int lineIndex(int n, int axis) {
  const int i = n >> (2 * kBlockLog2), j = (n >> kBlockLog2) & (kBlockDim - 1), k = n & (kBlockDim - 1);
  return axis == 0 ? j * kBlockDim + k : axis == 1 ? i * kBlockDim + k : i * kBlockDim + j;
}
} // namespace

/// The block of the line through block c along `axis`: c with that coordinate zeroed.
static BlockCoord lineBlock(const BlockCoord& c, int axis) {
  BlockCoord k = c;
  (axis == 0 ? k.x : axis == 1 ? k.y : k.z) = 0;
  return k;
}

uint64_t FlowColumns::lineKey(const BlockCoord& c, int axis) { return blockKey(lineBlock(c, axis)); }

void FlowColumns::build(const SparseGrid& grid, int volumeChannel) {
  static_assert(sizeof(Vec4) == 4 * sizeof(Real), "node masses are read 4 Reals apart");
  scratch_.clear();
  const size_t C = size_t(grid.channels.count);
  for (uint32_t b = 0; b < grid.blockCount(); ++b)
    scratch_.push_back({grid.topology.coord(b), grid.blockExtra(b) + volumeChannel, C, grid.block(b)->data(), 4});
  build(scratch_);
}

void FlowColumns::build(const std::vector<BlockFlow>& blocks) {
  const size_t N = blocks.size();
  // Each block's nodes with flow, in node order, packed (count, then offsets, then the nodes): the
  // lines of all three axes read only these.
  std::vector<uint32_t> count(N), start(N + 1, 0);
  auto eachFlowNode = [&](size_t i, auto&& f) {
    const BlockFlow& b = blocks[i];
    for (int n = 0; n < kBlockNodes; ++n) {
      const float v = b.volume[size_t(n) * b.volumeStride];
      if (v > 0) f(n, v, float(b.mass[size_t(n) * b.massStride]));
    }
  };
  tbb::parallel_for(tbb::blocked_range<size_t>(0, N, 16), [&](const auto& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      uint32_t k = 0;
      eachFlowNode(i, [&](int, float, float) { ++k; });
      count[i] = k;
    }
  });
  for (size_t i = 0; i < N; ++i) start[i + 1] = start[i] + count[i];
  nodes_.resize(start[N]);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, N, 16), [&](const auto& r) {
    for (size_t i = r.begin(); i != r.end(); ++i) {
      FlowNode* out = nodes_.data() + start[i];
      eachFlowNode(i, [&](int n, float v, float m) { *out++ = {uint16_t(n), v, m}; });
    }
  });
  // Which line each block with flow adds to, in the list's order (serial: a few hundred blocks).
  std::vector<uint32_t> lineOf(N);
  std::array<size_t, 4> offset{}; // lines of axes < a come first in the parallel passes
  for (int a = 0; a < 3; ++a) {
    auto& index = index_[a];
    index.clear();
    for (size_t i = 0; i < N; ++i)
      if (count[i]) lineOf[i] = index.try_emplace(lineKey(blocks[i].c, a), uint32_t(index.size())).first->second;
    const size_t nl = index.size();
    auto& first = first_[a];
    first.assign(nl + 1, 0);
    for (size_t i = 0; i < N; ++i)
      if (count[i]) ++first[lineOf[i] + 1];
    for (size_t l = 0; l < nl; ++l) first[l + 1] += first[l];
    members_[a].resize(first[nl]);
    std::vector<uint32_t> at(first.begin(), first.end() - 1);
    for (size_t i = 0; i < N; ++i)
      if (count[i]) members_[a][at[lineOf[i]]++] = uint32_t(i);
    lines_[a].resize(nl);
    offset[size_t(a) + 1] = offset[size_t(a)] + nl;
  }
  auto forEachLine = [&](auto&& f) {
    tbb::parallel_for(tbb::blocked_range<size_t>(0, offset[3], 4), [&](const auto& r) {
      for (size_t t = r.begin(); t != r.end(); ++t) {
        const int a = t < offset[1] ? 0 : t < offset[2] ? 1 : 2;
        f(a, t - offset[size_t(a)]);
      }
    });
  };
  forEachLine([&](int a, size_t l) {
    Line& L = lines_[a][l];
    std::fill(std::begin(L.volume), std::end(L.volume), 0.f);
    std::fill(std::begin(L.mass), std::end(L.mass), 0.f);
    L.at = lineBlock(blocks[members_[a][first_[a][l]]].c, a);
    for (uint32_t m = first_[a][l]; m < first_[a][l + 1]; ++m) {
      const uint32_t b = members_[a][m];
      for (uint32_t e = start[b]; e < start[b + 1]; ++e) {
        const int i = lineIndex(nodes_[e].node, a);
        L.volume[i] += nodes_[e].volume;
        L.mass[i] += nodes_[e].mass;
      }
    }
  });
  forEachLine([&](int a, size_t l) { dilate(a, l); });
}

void FlowColumns::dilate(int axis, size_t index) {
  // In-plane coordinates of a line block: (y, z), (x, z) or (x, y), as lineIndex orders them.
  auto coord = [axis](BlockCoord& c, int d) -> int32_t& { return d == 0 ? (axis == 0 ? c.y : c.x) : (axis == 2 ? c.y : c.z); };
  Line& line = lines_[axis][index];
  const Line* nb[3][3];
  for (int du = -1; du <= 1; ++du)
    for (int dv = -1; dv <= 1; ++dv) {
      BlockCoord c = line.at;
      coord(c, 0) += du, coord(c, 1) += dv;
      const auto it = index_[axis].find(blockKey(c));
      nb[du + 1][dv + 1] = it == index_[axis].end() ? nullptr : &lines_[axis][it->second];
    }
  for (int u = 0; u < kBlockDim; ++u)
    for (int v = 0; v < kBlockDim; ++v) {
      float w = 0;
      for (int du = -1; du <= 1; ++du)
        for (int dv = -1; dv <= 1; ++dv) {
          const int U = u + du, V = v + dv;
          const int bu = U < 0 ? 0 : U >= kBlockDim ? 2 : 1, bv = V < 0 ? 0 : V >= kBlockDim ? 2 : 1;
          if (const Line* l = nb[bu][bv])
            w = std::max(w, l->volume[((U + kBlockDim) % kBlockDim) * kBlockDim + (V + kBlockDim) % kBlockDim]);
        }
      line.widest[u * kBlockDim + v] = w;
    }
}

FlowColumns::BlockLines FlowColumns::lines(const BlockCoord& c) const {
  BlockLines out{};
  for (int a = 0; a < 3; ++a) {
    auto it = index_[a].find(lineKey(c, a));
    out[size_t(a)] = it == index_[a].end() ? nullptr : &lines_[a][it->second];
  }
  return out;
}

void FlowColumns::at(const BlockLines& L, int node, const Vec3& n, Real dx, Real& h, Real& rho) {
  const int a = axisOf(n);
  h = 0, rho = 0;
  const Line* line = L[size_t(a)];
  if (!line) return;
  const int i = lineIndex(node, a);
  const float v = line->volume[i];
  if (!(v > 0)) return;
  h = Real(line->widest[i]) / (dx * dx) * std::abs(n[a]);
  rho = Real(line->mass[i] / v);
}

} // namespace talus
