// Solid shapes that [[bodies]] fill with particles (local frame).
#pragma once

#include "engine/config_table.h"
#include "engine/types.h"

#include <memory>
#include <string>

namespace talus {

class BodyShape {
public:
  virtual ~BodyShape() = default;
  virtual bool contains(const Vec3d& x) const = 0;
  virtual void bounds(Vec3d& lo, Vec3d& hi) const = 0;
  virtual double volume() const = 0;
  virtual Vec3d centre() const = 0;
  /// Exact signed distance (negative inside).
  virtual double distance(const Vec3d& x) const = 0;
};

/// Reads `shape` and its keys from a [[bodies]] table: box (min/max, or center/size with an
/// optional rotation = [rx, ry, rz] in degrees applied as Rz Ry Rx), sphere (center, radius),
/// cylinder (start, end, radius). `origin` converts world coordinates to the local frame.
/// `key` names the selector ("shape" for [[bodies]], "solid" for fixed regions).
std::unique_ptr<BodyShape> readBodyShape(const ConfigTable& body, const Vec3d& origin, const std::string& key = "shape");

} // namespace talus
