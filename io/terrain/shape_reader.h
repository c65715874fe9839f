// Reads an analytic solid (engine/shapes.h) from a scene table: [[bodies]] shapes, fixed solids, structures.
#pragma once

#include "io/config/config_table.h"
#include "engine/shapes.h"

#include <memory>
#include <string>

namespace talus {

/// Reads `shape` and its keys from a [[bodies]] table: box (min/max, or center/size with an
/// optional rotation = [rx, ry, rz] in degrees applied as Rz Ry Rx), sphere (center, radius),
/// cylinder (start, end, radius). `origin` converts world coordinates to the local frame.
/// `key` names the selector ("shape" for [[bodies]], "solid" for fixed regions).
std::unique_ptr<Shape> readBodyShape(const ConfigTable& body, const Vec3d& origin, const std::string& key = "shape");

} // namespace talus
