// Flow thickness for basal laws that need it (Voellmy, samosAT): the flow's volume summed along
// grid lines. For a node in contact with normal n, the line through it along the grid axis closest
// to n holds the flow's volume per unit area normal to that axis; times |n_axis| it is the
// thickness along the normal of a flow parallel to the surface (the vertical column of a slope:
// h_normal = h_vertical cos(slope)). The line's mass over its volume is the flow's density. A line
// crossing two flows (over an overhang, both sides of a thin ridge) adds them.
//
// The B-spline spreads a flow's volume over the lines next to it too, so a line just beyond the
// flow's margin holds a sliver of it; a node there, though it carries the flow's margin, would read
// a thickness near zero and a rate law (drag ~ 1/h) would stop it dead, dragging the particles it
// touches (measured on Wolfsgruben at dx 5 m: h 0.001 m at light contact nodes, 1 m under the
// flow). A node therefore reads the thickest line among its own and the eight next to it.
#pragma once

#include "engine/sparse_grid.h"

#include <array>
#include <cmath>
#include <unordered_map>
#include <vector>

namespace talus {

class FlowColumns {
public:
  /// One block's node volumes and masses: node n's at volume[n * volumeStride], mass[n * massStride].
  struct BlockFlow {
    BlockCoord c;
    const float* volume;
    size_t volumeStride;
    const Real* mass;
    size_t massStride;
  };
  /// Sums P2G's volume channel (grid.extra, channel `volumeChannel`) and node masses per line.
  void build(const SparseGrid& grid, int volumeChannel);
  /// The same from a list of blocks (MPI ranks gather every rank's blocks in tree order). Each line
  /// adds its blocks in the list's order, so the sums are the same at any thread count.
  void build(const std::vector<BlockFlow>& blocks);

  /// The lines through a block, one per axis (null where no flow).
  struct Line {
    float volume[kBlockDim * kBlockDim] = {};
    float mass[kBlockDim * kBlockDim] = {};
    float widest[kBlockDim * kBlockDim] = {}; ///< largest volume among the line and its 8 neighbours
    BlockCoord at;                             ///< the block (its coordinate along the line zeroed)
  };
  using BlockLines = std::array<const Line*, 3>;
  BlockLines lines(const BlockCoord& c) const;

  /// The axis (0, 1, 2) of the line a node with contact normal n reads: the one closest to n.
  static int axisOf(const Vec3& n) {
    int a = 0;
    for (int d = 1; d < 3; ++d)
      if (std::abs(n[d]) > std::abs(n[a])) a = d;
    return a;
  }
  /// Thickness along the unit normal n (m) and density (kg/m3) at node n of a block with lines L.
  static void at(const BlockLines& L, int node, const Vec3& n, Real dx, Real& h, Real& rho);

  /// Key of the line through block c along axis: the same for every block of the line.
  static uint64_t lineKey(const BlockCoord& c, int axis);

private:
  void dilate(int axis, size_t line);
  // Per axis: the lines (storage kept between steps), their index by key, and which blocks (indices
  // into build's list) each line sums, as offsets into `members_`.
  std::vector<Line> lines_[3];
  std::unordered_map<uint64_t, uint32_t> index_[3];
  std::vector<uint32_t> first_[3], members_[3];
  std::vector<BlockFlow> scratch_;
  struct FlowNode {
    uint16_t node;
    float volume, mass;
  };
  std::vector<FlowNode> nodes_; ///< the nodes with flow of build's blocks, block after block
};

} // namespace talus
