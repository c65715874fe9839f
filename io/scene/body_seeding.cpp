#include "io/scene/body_seeding.h"

#include <cmath>
#include <cstdio>

namespace talus {

namespace {

std::string range(double a, double b) {
  char s[64];
  std::snprintf(s, sizeof s, "[%.10g, %.10g]", a, b);
  return s;
}

/// Velocity gradient of a rigid rotation: v = omega x r  =>  grad v = [omega]x.
Mat3d skew(const Vec3d& w) {
  Mat3d m;
  m << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return m;
}

} // namespace

std::string thinBodyNote(const BodyReport& body, double dx) {
  const double cells = body.meanThickness / dx;
  if (!(body.meanThickness > 0) || cells >= kThinBodyCells || body.kind == "fixed") return "";
  // The remedy measured on the idealised slope: 64 particles per cell on the body at 0.49 cells.
  char remedy[96];
  if (body.particlesPerCell >= 64)
    std::snprintf(remedy, sizeof remedy, "its %d particles per cell are the lighter remedy", body.particlesPerCell);
  else
    std::snprintf(remedy, sizeof remedy, "particles_per_cell = 64 on the body (now %d) is a lighter remedy",
                  body.particlesPerCell);
  char s[640];
  std::snprintf(s, sizeof s,
                "warning: %s is %.3g m thick on average (vertical), %.2g cells at dx %g m: below one cell across, "
                "peak flow heights come out too high (+48 %% at 0.49 cells, +11 %% at 0.98 on an idealised slope, 8 "
                "particles per cell; within 9 %% at 0.49 cells with 64) while run-out and speed stay within 4 %%; %s, "
                "and dx <= %.3g m puts a cell across it (docs/convergence.md, \"Thin releases\")",
                body.label.c_str(), body.meanThickness, cells, dx, remedy, body.meanThickness / kThinBodyCells);
  return s;
}

BodyReport seedShapeBody(const ConfigTable& t, const Shape& shape, const SeedSpec& spec, const Vec3d& domainMin,
                         const Vec3d& domainMax, MaterialGroup& group) {
  BodyReport rep;
  rep.material = group.name();
  rep.kind = t.string("shape");
  Vec3d lo, hi;
  shape.bounds(lo, hi);
  const double tol = 1e-9 * (1 + domainMax.cwiseAbs().maxCoeff());
  if ((lo.array() < domainMin.array() - tol).any() || (hi.array() > domainMax.array() + tol).any())
    t.fail("shape", "body extends outside the domain");
  const Vec3d v0 = t.vec3("velocity", Vec3d::Zero());
  const Vec3d omega = t.vec3("angular_velocity", Vec3d::Zero());
  const Vec3d c = shape.centre();
  rep.particles = seedRegion(
      lo, hi, [&](const Vec3d& x) { return shape.contains(x); },
      [&](const Vec3d& x) { return Vec3d(v0 + omega.cross(x - c)); }, spec, group, skew(omega));
  if (rep.particles == 0) t.fail("shape", "body holds no particle (smaller than a cell, or inside the terrain)");
  rep.seededVolume = double(rep.particles) * std::pow(spec.dx, 3) / spec.particlesPerCell;
  rep.geometricVolume = shape.volume();
  return rep;
}

/// A layer thinner than a few particle spacings is sampled by whichever lattice levels fall
/// inside it, so its particle count misses its volume by several percent (5 % for Wolfsgruben's
/// 1 m release at dx 10 m). A release then scales its particles' masses (and with them their
/// volumes, m / rho) so that it holds its geometric volume, the polygon times the thickness that
/// com1DFA releases. Left alone beyond +-20 %: the body then overlaps a structure or an earlier
/// body, which its geometric volume does not subtract.
namespace {
void matchVolume(const ConfigTable& t, const TerrainBody& body, BodyReport& rep, MaterialGroup& group, size_t first) {
  if (!t.boolean("match_volume", body.kind() == TerrainBody::Kind::Release)) return;
  const double f = rep.geometricVolume / rep.seededVolume;
  if (!(f > 0.8 && f < 1.25)) return;
  auto& mass = group.particles.mass;
  for (size_t p = first; p < mass.size(); ++p) mass[p] = Real(double(mass[p]) * f);
  rep.massScale = f;
}
} // namespace

BodyReport seedTerrainBody(const TerrainBody& body, const HeightField& bed, const SeedSpec& spec, const Vec3d& origin,
                           const Vec3d& domainMin, const Vec3d& domainMax, MaterialGroup* group,
                           const std::vector<const TerrainBody*>& earlier) {
  const ConfigTable& t = body.table();
  BodyReport rep;
  rep.kind = body.kindName();
  rep.material = group ? group->name() : "";
  if (body.solid()) {
    rep.geometricVolume = body.solid()->volume();
    return rep;
  }
  Vec3d lo, hi;
  const double q = 0.5 * std::min(spec.dx, body.grid().cellSize);
  double area = 0;
  rep.geometricVolume = body.measure(bed, q, lo, hi, &area);
  if (area > 0) rep.meanThickness = rep.geometricVolume / area;
  rep.particlesPerCell = spec.particlesPerCell;
  const std::string key = body.regionKey();
  if (!(rep.geometricVolume > 0)) {
    const char* why = body.kind() == TerrainBody::Kind::Water ? "the terrain is nowhere below 'level' in the region"
                      : body.kind() == TerrainBody::Kind::Layer ? "no part of the region passes the slope and elevation limits"
                                             : "zero thickness everywhere";
    t.fail(key, std::string("the body is empty: ") + why);
  }
  const double tol = 1e-9 * (1 + domainMax.cwiseAbs().maxCoeff());
  if ((lo.array() < domainMin.array() - tol).any() || (hi.array() > domainMax.array() + tol).any())
    t.fail(key, "body extends outside the domain (body x " + range(lo.x(), hi.x()) + ", y " + range(lo.y(), hi.y()) +
                    ", z " + range(lo.z(), hi.z()) + ")");
  if (body.kind() == TerrainBody::Kind::Fixed) return rep;

  const Vec3d v0 = body.velocity();
  const double gridMargin = spec.dx;
  auto columnRange = [&](double x0, double y0, double x1, double y1, double& zlo, double& zhi) {
    zlo = INFINITY, zhi = -INFINITY;
    double gmax = 0;
    bool any = false;
    for (int a = 0; a < 3; ++a)
      for (int b = 0; b < 3; ++b) {
        const double x = origin.x() + x0 + 0.5 * a * (x1 - x0), y = origin.y() + y0 + 0.5 * b * (y1 - y0);
        double gx, gy;
        const double zb = bed.heightAndGradient(x, y, gx, gy);
        gmax = std::max(gmax, std::hypot(gx, gy));
        const double top = body.columnTopBound(bed, x, y, zb);
        any |= top > zb;
        zlo = std::min(zlo, zb), zhi = std::max(zhi, top);
      }
    const double m = gridMargin * (1 + gmax);
    zlo -= origin.z() + m, zhi += m - origin.z();
    return any;
  };
  auto inside = [&](const Vec3d& x) {
    const Vec3d w = origin + x;
    if (!body.contains(bed, w.x(), w.y(), w.z())) return false;
    for (const TerrainBody* e : earlier)
      if (e->kind() != TerrainBody::Kind::Fixed && e->contains(bed, w.x(), w.y(), w.z())) return false;
    return true;
  };
  // The quadrature bounds z only to within a sample spacing: pad (columnRange bounds the cells).
  const Vec3d pad(0, 0, 10 * spec.dx);
  const size_t first = group->particles.size();
  auto seed = [&](const SeedSpec& sp) {
    return seedColumns(lo - origin - pad, hi - origin + pad, columnRange, inside, [&](const Vec3d&) { return v0; }, sp,
                       *group);
  };
  rep.particles = seed(spec);
  if (rep.particles == 0 && spec.latticeDecides) { // thinner than the spacing: no lattice point inside
    SeedSpec jittered = spec;
    jittered.latticeDecides = false;
    rep.particles = seed(jittered);
  }
  rep.seededVolume = double(rep.particles) * std::pow(spec.dx, 3) / spec.particlesPerCell;
  if (rep.particles == 0) t.fail(key, "body holds no particle (thinner than the particle spacing, or inside the terrain)");
  matchVolume(t, body, rep, *group, first);
  return rep;
}

bool holdSecondaryRelease(const ConfigTable& t, const std::string& label, MaterialGroup& group, int position,
                          size_t first, std::vector<HeldBody>& held) {
  if (!t.has("trigger_thickness")) return false;
  HeldBody h;
  h.name = label;
  h.group = position;
  h.triggerMassPerArea = group.density() * t.positive("trigger_thickness");
  ParticleSet& P = group.particles;
  h.x.assign(P.x.begin() + long(first), P.x.end());
  h.mass.assign(P.mass.begin() + long(first), P.mass.end());
  P.x.resize(first), P.v.resize(first), P.C.resize(first), P.tau.resize(first), P.mass.resize(first);
  group.resizeState(first);
  held.push_back(std::move(h));
  return true;
}

} // namespace talus
