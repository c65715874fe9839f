// Periodic domain axes: material leaving one face re-enters at the other. Used for flows that
// are uniform along an axis (an infinite slope, a uniform channel), so a few cells stand for an
// unbounded layer: the steady uniform flows of the basal-law and rheology validations.
//
// The period must be a whole number of 8-node blocks, so a node and its image sit at the same
// place in their blocks. Each step P2G scatters as usual, ghost nodes outside [lo, lo + n) are
// folded into their images (added, then emptied) before the grid update, and after it the
// images' velocities are copied back to the ghosts for G2P; particles are wrapped into the period
// after they move.
#pragma once

#include "engine/sparse_grid.h"

#include <vector>

namespace talus {

struct Periodicity {
  bool axis[3] = {false, false, false};
  int lo[3] = {0, 0, 0}; ///< first node index of the period per axis
  int n[3] = {0, 0, 0};  ///< period in nodes (a multiple of kBlockDim)

  bool any() const { return axis[0] || axis[1] || axis[2]; }
  /// The blocks the images of `blocks` need (ghost nodes fold into them): appended to `blocks`.
  void addImages(std::vector<BlockCoord>& blocks) const;
  /// Folds ghost nodes (mass, momentum and extra channels) into their images and empties them.
  void fold(SparseGrid& grid) const;
  /// Copies the images' (mass, velocity) back to the ghost nodes.
  void unfold(SparseGrid& grid) const;
  /// Wraps a coordinate (local frame, metres) into [lo dx, (lo + n) dx) along an axis.
  Real wrap(int a, Real x, Real dx) const;
};

} // namespace talus
