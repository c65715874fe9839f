// Quadratic B-spline stencil of one particle: 3 nodes per axis starting at `base`.
#pragma once

#include "engine/types.h"

#include <cmath>

namespace talus {

/// floor(v) as an int, for |v| < 2^31 (a grid index: positions are finite and inside the
/// domain). The same value as int(std::floor(v)), in about half the instructions: without SSE4.1
/// (the default build's target) GCC expands std::floor into a branch and two conversions.
inline int floorToInt(Real v) {
  const int i = int(v); // truncates toward zero
  return i - int(v < Real(i));
}

struct QuadraticStencil {
  int base[3];   ///< global index of the first stencil node per axis
  Real f[3];     ///< particle position minus base, in cells, in [0.5, 1.5)
  Real w[3][3];  ///< weights per axis and stencil node

  QuadraticStencil() = default;
  /// `xs` is the particle position in grid units (x / dx).
  explicit QuadraticStencil(const Vec3& xs) {
    for (int d = 0; d < 3; ++d) {
      base[d] = floorToInt(xs[d] - Real(0.5));
      const Real fx = xs[d] - Real(base[d]);
      f[d] = fx;
      const Real a = Real(1.5) - fx, b = fx - Real(1), c = fx - Real(0.5);
      w[d][0] = Real(0.5) * a * a;
      w[d][1] = Real(0.75) - b * b;
      w[d][2] = Real(0.5) * c * c;
    }
  }
};

/// Block that owns a particle: the block of its stencil's base node.
inline BlockCoord owningBlock(const Vec3& x, Real invDx) {
  BlockCoord c;
  c.x = floorToInt(x[0] * invDx - Real(0.5)) >> kBlockLog2;
  c.y = floorToInt(x[1] * invDx - Real(0.5)) >> kBlockLog2;
  c.z = floorToInt(x[2] * invDx - Real(0.5)) >> kBlockLog2;
  return c;
}

} // namespace talus
