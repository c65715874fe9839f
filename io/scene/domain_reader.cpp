#include "io/scene/domain_reader.h"

#include "engine/collider.h"
#include "io/scene/contact_law_table.h"
#include "io/terrain/dem_raster.h"
#include "io/terrain/terrain_loader.h"

#include <cmath>
#include <cstdio>

namespace talus {

namespace {

/// `periodic = ["x", "y"]`: those axes wrap around; their extent must be whole 8-node blocks.
void readPeriodic(const ConfigTable& dom, SceneSetup& s) {
  for (const std::string& a : dom.strings("periodic")) {
    if (a != "x" && a != "y" && a != "z") dom.fail("periodic", "'" + a + "' is not an axis (x, y or z)");
    const int d = a[0] - 'x';
    const double dx = s.settings.dx, lo = s.settings.domain.min[d] / dx;
    const double n = (s.settings.domain.max[d] - s.settings.domain.min[d]) / dx;
    if (std::abs(lo - std::round(lo)) > 1e-6 || std::abs(n - std::round(n)) > 1e-6 || std::lround(n) % kBlockDim != 0)
      dom.fail("periodic", "a periodic " + a + " axis needs domain.min on a grid node and an extent of a multiple of 8 dx (" +
                               std::to_string(8 * dx) + " m); the domain spans " + std::to_string(n) + " cells");
    for (int side = 0; side < 2; ++side)
      if (dom.has(faceNames()[size_t(2 * d + side)]))
        dom.fail(faceNames()[size_t(2 * d + side)], "the " + a + " axis is periodic: its faces have no law");
    s.settings.periodic[size_t(d)] = true;
    s.settings.faces[size_t(2 * d)] = s.settings.faces[size_t(2 * d + 1)] = nullptr;
  }
}

/// A wall holds the grid nodes at or beyond its face, so a face between two node rows acts at
/// the row beyond it (Collider::faceRow; the cull box follows it): the material
/// has up to a cell more room than the box says. Said once per such face.
void noteWallsOffNodes(SceneSetup& s) {
  const double dx = s.settings.dx;
  for (size_t f = 0; f < 6; ++f) {
    const int axis = int(f / 2);
    const bool upper = f % 2;
    if (!s.settings.faces[f] || s.settings.periodic[size_t(axis)]) continue;
    const double at = upper ? s.settings.domain.max[axis] : s.settings.domain.min[axis];
    const double row = double(Collider::faceRow(at, dx, upper)) * dx;
    if (std::abs(row - at) <= 1e-6 * dx) continue;
    char buf[320];
    std::snprintf(buf, sizeof buf,
                  "domain: the %s wall (%.6g m) lies between grid node rows (dx %.6g m) and acts at the row beyond, "
                  "%.6g m: %.3g m more room; put the domain's faces on multiples of dx from the origin",
                  faceNames()[f], at + s.settings.origin[axis], dx, row + s.settings.origin[axis], std::abs(row - at));
    s.notes.push_back(buf);
  }
}

} // namespace

void readDomain(const ConfigTable& root, SceneSetup& s, const DemTerrainInput* dem) {
  const ConfigTable* dom = root.table("domain");
  if (!dom && !dem) root.fail("", "missing [domain] section");
  Vec3d lo, hi;
  const bool box = dom && (dom->has("min") || dom->has("max"));
  if (!dem || box) {
    lo = dom->vec3("min"), hi = dom->vec3("max");
    for (int d = 0; d < 3; ++d)
      if (!(hi[d] > lo[d])) dom->fail("max", "must exceed domain.min on every axis");
  }
  if (dem) {
    const HeightField f(*dem->smoothed);
    float hmin, hmax;
    f.range(hmin, hmax);
    const double dx = s.settings.dx;
    if (!box) {
      lo = Vec3d(f.xmin(), f.ymin(), hmin - 8 * dx);
      hi = Vec3d(f.xmax(), f.ymax(), hmax + std::max(100.0, 20 * dx));
    } else {
      const double tol = 1e-6 * f.grid().cellSize;
      if (lo.x() < f.xmin() - tol || hi.x() > f.xmax() + tol || lo.y() < f.ymin() - tol || hi.y() > f.ymax() + tol) {
        char buf[320];
        std::snprintf(buf, sizeof buf, "the domain (x [%.10g, %.10g], y [%.10g, %.10g]) extends beyond the DEM "
                      "(x [%.10g, %.10g], y [%.10g, %.10g])", lo.x(), hi.x(), lo.y(), hi.y(), f.xmin(), f.xmax(),
                      f.ymin(), f.ymax());
        dom->fail("min", buf);
      }
    }
  }
  // Local frame: national grid coordinates (~1e6 m) would lose metres in single precision.
  s.settings.origin = dom ? dom->vec3("origin", lo) : lo;
  s.settings.domain.min = lo - s.settings.origin;
  s.settings.domain.max = hi - s.settings.origin;
  if (dom) {
    // `walls` for all six faces, each face overridable: x_max = "open", z_min = { law = ... }.
    const auto walls = readContactLaw(*dom, "walls", "slip", "wall_", true);
    for (size_t f = 0; f < 6; ++f)
      s.settings.faces[f] = dom->has(faceNames()[f]) ? readContactLaw(*dom, faceNames()[f], "", "wall_", true) : walls;
    if (dom->has("periodic")) readPeriodic(*dom, s);
    noteWallsOffNodes(s);
  }
}

} // namespace talus
