// A plug (a stiff slab filling a periodic 8 x 8-cell patch, so an infinite layer) on a terrain
// plane with Coulomb friction `mu`, the slope made by tilting gravity 30 degrees, under a
// resistance region (a forest, AvaFrame's RES/) over the whole patch. Shared by the forest's drag
// (test_basal_laws.cpp) and detrainment (test_detrainment.cpp) tests.
#pragma once

#include "terrain_test_support.h"

#include <cmath>
#include <cstdio>
#include <string>

namespace talus::test {

/// The plug's material and body: an elastic slab of thickness h over the 8 x 8-cell patch, moving
/// at `speed` along x.
inline std::string plugSlab(double dx, double h, double speed = 0) {
  char buf[400];
  std::snprintf(buf, sizeof buf, R"(
[[materials]]
name = "slab"
model = "elastic"
density = 300
youngs_modulus = 1e6
poisson_ratio = 0.3
[[bodies]]
material = "slab"
shape = "box"
min = [0, 0, 0]
max = [%g, %g, %g]
velocity = [%g, 0, 0]
)",
                8 * dx, 8 * dx, h, speed);
  return buf;
}

/// `regionKeys`: more keys of the resistance region (e.g. "detrainment = 0"); `speed`: the slab's
/// initial speed down the slope (m/s). The polygon is written to `dir`/forest.geojson.
inline std::string forestPlugScene(const std::string& dir, double h, double dx, double mu, double cRes, double ramp,
                                   const std::string& regionKeys = "", double speed = 0) {
  writePolygons(dir + "/forest.geojson", {{rectangleRing(-10, -10, 20, 20), 0.0}}, "", "GeoJSON");
  const double t = 30 * M_PI / 180, g = 9.81;
  char buf[1800];
  std::snprintf(buf, sizeof buf, R"(
[simulation]
dx = %g
end_time = 100
gravity = [%.12g, 0, %.12g]
gravity_ramp = %g
[domain]
min = [0, 0, %g]
max = [%g, %g, %g]
periodic = ["x", "y"]
walls = "slip"
[terrain]
plane = { point = [0, 0, 0], normal = [0, 0, 1] }
boundary = "friction"
friction = %.12g
[[terrain.regions]]
polygon = "%s/forest.geojson"
resistance = %g
%s
)",
                dx, g * std::sin(t), -g * std::cos(t), ramp, -4 * dx, 8 * dx, 8 * dx, h + 8 * dx, mu, dir.c_str(), cRes,
                regionKeys.c_str());
  return buf + plugSlab(dx, h, speed);
}

} // namespace talus::test
