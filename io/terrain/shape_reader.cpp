#include "io/terrain/shape_reader.h"

#include <Eigen/Geometry>
#include <cmath>

namespace talus {

std::unique_ptr<Shape> readBodyShape(const ConfigTable& t, const Vec3d& origin, const std::string& key) {
  const std::string shape = t.choice(key, "", {"box", "sphere", "cylinder"});
  if (shape == "box") {
    Mat3d R = Mat3d::Identity();
    if (t.has("rotation")) {
      const Vec3d a = t.vec3("rotation") * (M_PI / 180.0);
      R = (Eigen::AngleAxisd(a.z(), Vec3d::UnitZ()) * Eigen::AngleAxisd(a.y(), Vec3d::UnitY()) *
           Eigen::AngleAxisd(a.x(), Vec3d::UnitX())).toRotationMatrix();
    }
    if (t.has("min") || t.has("max")) {
      if (t.has("center") || t.has("size")) t.fail("min", "give either min/max or center/size, not both");
      const Vec3d lo = t.vec3("min"), hi = t.vec3("max");
      for (int d = 0; d < 3; ++d)
        if (!(hi[d] > lo[d])) t.fail("max", "must exceed min on every axis");
      return makeBox(0.5 * (lo + hi) - origin, hi - lo, R);
    }
    const Vec3d size = t.vec3("size");
    if (!(size.minCoeff() > 0)) t.fail("size", "must be positive on every axis");
    return makeBox(t.vec3("center") - origin, size, R);
  }
  if (shape == "sphere") return makeSphere(t.vec3("center") - origin, t.positive("radius"));
  const Vec3d a = t.vec3("start"), b = t.vec3("end");
  if (!((b - a).norm() > 0)) t.fail("end", "must differ from start");
  return makeCylinder(a - origin, b - origin, t.positive("radius"));
}

} // namespace talus
