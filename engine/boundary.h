// Boundary conditions applied to grid velocities (physics.md section 6).
#pragma once

#include "engine/types.h"

#include <cmath>
#include <string>

namespace talus {

enum class BoundaryType { Sticky, Slip, Friction, Open };

struct BoundaryCondition {
  BoundaryType type = BoundaryType::Slip;
  Real friction = 0; ///< Coulomb coefficient for BoundaryType::Friction
};

const char* boundaryTypeName(BoundaryType t);

/// Velocity of a node that lies inside a boundary with outward unit normal n (boundary at rest).
/// Slip and friction act only when the node moves into the boundary (separating contact).
inline Vec3 boundaryVelocity(const Vec3& v, const Vec3& n, const BoundaryCondition& bc) {
  switch (bc.type) {
  case BoundaryType::Open:
    return v;
  case BoundaryType::Sticky:
    return Vec3::Zero();
  case BoundaryType::Slip: {
    const Real vn = v.dot(n);
    return vn < 0 ? Vec3(v - vn * n) : v;
  }
  case BoundaryType::Friction: {
    const Real vn = v.dot(n);
    if (vn >= 0) return v;
    const Vec3 vt = v - vn * n;
    const Real vtNorm = vt.norm();
    if (vtNorm <= bc.friction * -vn) return Vec3::Zero(); // static friction holds
    return (Real(1) + bc.friction * vn / vtNorm) * vt;
  }
  }
  return v;
}

/// Axis-aligned domain box in the local frame. Nodes on or beyond a face take the wall
/// condition; particles more than half a cell beyond it are removed and their mass reported.
struct DomainBox {
  Vec3d min = Vec3d::Zero(), max = Vec3d::Ones();
  BoundaryCondition walls;
};

} // namespace talus
