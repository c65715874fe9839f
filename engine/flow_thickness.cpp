#include "engine/flow_thickness.h"

#include <algorithm>
#include <cmath>

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

void FlowColumns::clear() {
  for (auto& l : lines_) l.clear();
}

void FlowColumns::addBlock(const BlockCoord& c, const float* volume, const float* mass) {
  Line* L[3] = {nullptr, nullptr, nullptr};
  for (int n = 0; n < kBlockNodes; ++n) {
    const float v = volume[n];
    if (!(v > 0)) continue;
    for (int a = 0; a < 3; ++a) {
      if (!L[a]) {
        L[a] = &lines_[a][lineKey(c, a)];
        L[a]->at = lineBlock(c, a);
      }
      L[a]->volume[lineIndex(n, a)] += v;
      L[a]->mass[lineIndex(n, a)] += mass[n];
    }
  }
}

void FlowColumns::finish() {
  for (int a = 0; a < 3; ++a) dilate(a);
}

void FlowColumns::build(const SparseGrid& grid, int volumeChannel) {
  clear();
  const int C = grid.extraChannels;
  float volume[kBlockNodes], mass[kBlockNodes];
  // Serial in block order: the sums are the same at any thread count.
  for (uint32_t b = 0; b < grid.blockCount(); ++b) {
    const Vec4* nodes = grid.block(b);
    const float* extra = grid.blockExtra(b);
    for (int n = 0; n < kBlockNodes; ++n) {
      volume[n] = extra[size_t(n) * size_t(C) + size_t(volumeChannel)];
      mass[n] = float(nodes[n][0]);
    }
    addBlock(grid.topology.coord(b), volume, mass);
  }
  finish();
}

void FlowColumns::dilate(int axis) {
  // In-plane coordinates of a line block: (y, z), (x, z) or (x, y), as lineIndex orders them.
  auto coord = [axis](BlockCoord& c, int d) -> int32_t& { return d == 0 ? (axis == 0 ? c.y : c.x) : (axis == 2 ? c.y : c.z); };
  for (auto& [key, line] : lines_[axis]) {
    const Line* nb[3][3];
    for (int du = -1; du <= 1; ++du)
      for (int dv = -1; dv <= 1; ++dv) {
        BlockCoord c = line.at;
        coord(c, 0) += du, coord(c, 1) += dv;
        const auto it = lines_[axis].find(blockKey(c));
        nb[du + 1][dv + 1] = it == lines_[axis].end() ? nullptr : &it->second;
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
}

FlowColumns::BlockLines FlowColumns::lines(const BlockCoord& c) const {
  BlockLines out{};
  for (int a = 0; a < 3; ++a) {
    auto it = lines_[a].find(lineKey(c, a));
    out[size_t(a)] = it == lines_[a].end() ? nullptr : &it->second;
  }
  return out;
}

void FlowColumns::at(const BlockLines& L, int node, const Vec3& n, Real dx, Real& h, Real& rho) {
  int a = 0;
  for (int d = 1; d < 3; ++d)
    if (std::abs(n[d]) > std::abs(n[a])) a = d;
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
