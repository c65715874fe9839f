// Analytic solids in the local frame: bodies filled with particles, fixed regions of the terrain,
// and the geometry of structures that colliders hold.
#pragma once

#include "engine/types.h"

#include <memory>

namespace talus {

class Shape {
public:
  virtual ~Shape() = default;
  virtual bool contains(const Vec3d& x) const = 0;
  virtual void bounds(Vec3d& lo, Vec3d& hi) const = 0;
  virtual double volume() const = 0;
  virtual Vec3d centre() const = 0;
  /// Exact signed distance (negative inside).
  virtual double distance(const Vec3d& x) const = 0;
};

/// Box of edge lengths `size` centred at `centre`, its axes the columns of rotation `R`.
std::unique_ptr<Shape> makeBox(const Vec3d& centre, const Vec3d& size, const Mat3d& R = Mat3d::Identity());
std::unique_ptr<Shape> makeSphere(const Vec3d& centre, double radius);
/// Solid cylinder with flat caps, axis from `start` to `end`.
std::unique_ptr<Shape> makeCylinder(const Vec3d& start, const Vec3d& end, double radius);

} // namespace talus
