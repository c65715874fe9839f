#include "io/scene.h"

#include "io/body_shapes.h"
#include "io/particle_seeding.h"
#include "io/terrain_loader.h"
#include "io/toml_reader.h"
#include "materials/material_factory.h"

#include <cmath>
#include <map>

namespace talus {

namespace {

/// Velocity gradient of a rigid rotation: v = omega x r  =>  grad v = [omega]x.
Mat3d skew(const Vec3d& w) {
  Mat3d m;
  m << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return m;
}

BoundaryCondition readBoundary(const ConfigTable& t, const std::string& typeKey, const std::string& frictionKey,
                               const std::string& fallback, bool allowOpen) {
  std::vector<std::string> kinds{"sticky", "slip", "friction"};
  if (allowOpen) kinds.push_back("open");
  const std::string s = t.choice(typeKey, fallback, kinds);
  BoundaryCondition bc;
  bc.type = s == "sticky" ? BoundaryType::Sticky : s == "slip" ? BoundaryType::Slip
            : s == "friction" ? BoundaryType::Friction : BoundaryType::Open;
  if (bc.type == BoundaryType::Friction) {
    if (!t.has(frictionKey)) t.fail(typeKey, "'friction' needs the Coulomb coefficient '" + frictionKey + "'");
    bc.friction = Real(t.inRange(frictionKey, 0, 0, 10));
  } else if (t.has(frictionKey)) {
    t.inRange(frictionKey, 0, 0, 10); // validated but unused by this boundary type
  }
  return bc;
}

void readSimulation(const ConfigTable& root, SceneSetup& s) {
  const ConfigTable* sim = root.table("simulation");
  if (!sim) root.fail("", "missing [simulation] section");
  s.settings.dx = sim->positive("dx");
  s.particlesPerCell = int(sim->integer("particles_per_cell", 8, 1, 64));
  s.endTime = sim->positive("end_time");
  s.settings.cfl = sim->inRange("cfl", 0.4, 0, 1, true, false);
  s.settings.gravity = sim->vec3("gravity", Vec3d(0, 0, -9.81));
  s.settings.maxDt = sim->positive("max_dt", std::numeric_limits<double>::infinity());
  s.settings.gravityRamp = sim->positive("gravity_ramp", 0, true);
}

void readDomain(const ConfigTable& root, SceneSetup& s) {
  const ConfigTable* dom = root.table("domain");
  if (!dom) root.fail("", "missing [domain] section");
  const Vec3d lo = dom->vec3("min"), hi = dom->vec3("max");
  for (int d = 0; d < 3; ++d)
    if (!(hi[d] > lo[d])) dom->fail("max", "must exceed domain.min on every axis");
  // Local frame: national grid coordinates (~1e6 m) would lose metres in single precision.
  s.settings.origin = dom->vec3("origin", lo);
  s.settings.domain.min = lo - s.settings.origin;
  s.settings.domain.max = hi - s.settings.origin;
  s.settings.domain.walls = readBoundary(*dom, "walls", "wall_friction", "slip", true);
}

void readTerrain(const ConfigTable& root, SceneSetup& s) {
  const ConfigTable* ter = root.table("terrain");
  if (!ter) return;
  s.settings.terrain = loadTerrain(*ter, s.settings);
  s.settings.terrainBoundary = readBoundary(*ter, "boundary", "friction", "friction", false);
}

void readMaterials(const ConfigTable& root, SceneSetup& s) {
  const auto tables = root.tables("materials");
  if (tables.empty()) root.fail("", "no [[materials]] given");
  for (size_t i = 0; i < tables.size(); ++i) {
    auto g = createMaterialGroup(*tables[i], int(i));
    for (const auto& n : s.materialNames)
      if (n == g->name()) tables[i]->fail("name", "duplicate material name '" + n + "'");
    s.materialNames.push_back(g->name());
    s.groups.push_back(std::move(g));
  }
}

void readBodies(const ConfigTable& root, SceneSetup& s, uint64_t seed, double jitter) {
  const auto tables = root.tables("bodies");
  if (tables.empty()) root.fail("", "no [[bodies]] given: the scene has nothing to simulate");
  SeedSpec spec;
  spec.dx = s.settings.dx;
  spec.particlesPerCell = s.particlesPerCell;
  spec.seed = seed;
  spec.jitter = jitter;
  spec.terrain = s.settings.terrain.get();
  const DomainBox& dom = s.settings.domain;
  for (size_t i = 0; i < tables.size(); ++i) {
    const ConfigTable& t = *tables[i];
    BodyReport rep;
    rep.label = t.string("name", "bodies[" + std::to_string(i) + "]");
    rep.material = t.string("material");
    MaterialGroup* group = nullptr;
    for (auto& g : s.groups)
      if (g->name() == rep.material) group = g.get();
    if (!group) {
      std::string list;
      for (const auto& n : s.materialNames) list += (list.empty() ? "" : ", ") + n;
      t.fail("material", "no material named '" + rep.material + "' (materials: " + list + ")");
    }
    auto shape = readBodyShape(t, s.settings.origin);
    rep.kind = t.string("shape");
    Vec3d lo, hi;
    shape->bounds(lo, hi);
    const double tol = 1e-9 * (1 + dom.max.cwiseAbs().maxCoeff());
    if ((lo.array() < dom.min.array() - tol).any() || (hi.array() > dom.max.array() + tol).any())
      t.fail("shape", "body extends outside the domain");
    const Vec3d v0 = t.vec3("velocity", Vec3d::Zero());
    const Vec3d omega = t.vec3("angular_velocity", Vec3d::Zero());
    const Vec3d c = shape->centre();
    rep.particles = seedRegion(
        lo, hi, [&](const Vec3d& x) { return shape->contains(x); },
        [&](const Vec3d& x) { return Vec3d(v0 + omega.cross(x - c)); }, spec, *group, skew(omega));
    if (rep.particles == 0) t.fail("shape", "body holds no particle (smaller than a cell, or inside the terrain)");
    rep.seededVolume = double(rep.particles) * std::pow(spec.dx, 3) / spec.particlesPerCell;
    rep.geometricVolume = shape->volume();
    s.bodies.push_back(rep);
  }
}

void readOutput(const ConfigTable& root, SceneSetup& s) {
  s.output = readOutputSettings(root.table("output"), s.materialNames);
}

} // namespace

SceneSetup buildScene(const ConfigTable& root) {
  SceneSetup s;
  s.file = root.file();
  readSimulation(root, s);
  readDomain(root, s);
  readTerrain(root, s);
  readMaterials(root, s);
  const ConfigTable* sim = root.table("simulation");
  const uint64_t seed = uint64_t(sim->integer("seed", 0, 0, INT64_MAX));
  const double jitter = sim->inRange("jitter", 0, 0, 1);
  readBodies(root, s, seed, jitter);
  readOutput(root, s);
  root.checkAllUsed();
  return s;
}

SceneSetup loadSceneFile(const std::string& path, const std::vector<std::string>& overrides) {
  auto root = readTomlFile(path);
  for (const auto& o : overrides) applyOverride(*root, o);
  return buildScene(*root);
}

SceneSetup loadSceneString(const std::string& text, const std::string& name,
                           const std::vector<std::string>& overrides) {
  auto root = readTomlString(text, name);
  for (const auto& o : overrides) applyOverride(*root, o);
  return buildScene(*root);
}

} // namespace talus
