#include "io/scene/scene.h"

#include "engine/resistance_law.h"
#include "engine/sdf_solids.h"
#include "io/terrain/shape_reader.h"
#include "io/scene/body_seeding.h"
#include "io/scene/erodible_cover_reader.h"
#include "io/scene/inflow_reader.h"
#include "io/common/resource_limits.h"
#include "io/terrain/terrain_bodies.h"
#include "io/terrain/terrain_loader.h"
#include "io/config/toml_reader.h"
#include "io/scene/avaframe_scene.h"
#include "io/scene/contact_law_table.h"
#include "io/scene/domain_reader.h"
#include "io/scene/model_table.h"
#include "io/scene/region_reader.h"
#include "io/scene/structure_reader.h"

#include <cmath>
#include <cstdio>
#include <map>
#include <optional>

namespace talus {

namespace {

/// FNV-1a, 64 bit, of `text` as 16 hex digits: names a configuration (peak files, checkpoints).
std::string fnv1aHex(const std::string& text) {
  uint64_t h = 1469598103934665603ull;
  for (unsigned char c : text) h = (h ^ c) * 1099511628211ull;
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return hex;
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
  s.settings.damping = sim->positive("damping", 0, true);
  s.settings.flip = sim->inRange("flip", 0, 0, 1);
  s.settings.fbar = sim->boolean("fbar", false);
  s.maxParticles = std::min(sim->positive("max_particles", 2e9), resourceLimits().maxParticles);
}

void readTerrain(const ConfigTable& root, SceneSetup& s) {
  const ConfigTable* ter = root.table("terrain");
  if (!ter) return;
  s.settings.terrain = loadTerrain(*ter, s.settings);
  readTerrainLaw(*ter, s.settings, "");
}

/// A DEM terrain: the ground edits of the terrain bodies (releases from a post-event DEM are
/// carved out, fixed layers added), then the level set at the simulation's dx with its voxels on
/// the grid nodes (cached), united with fixed solids. `bed` is the ground the bodies lie on.
void buildDemTerrain(const ConfigTable& ter, const DemTerrainInput& dem, const std::vector<const TerrainBody*>& bodies,
                     SceneSetup& s, std::shared_ptr<DemRaster>& bed) {
  bed = std::make_shared<DemRaster>(*dem.smoothed);
  for (const TerrainBody* b : bodies)
    if (!b->carveDepth().empty())
      for (size_t i = 0; i < bed->height.size(); ++i) bed->height[i] -= b->carveDepth()[i];
  auto ground = std::make_shared<DemRaster>(*bed);
  {
    const HeightField bedField(*bed);
    for (const TerrainBody* b : bodies) b->raise(bedField, *ground);
  }
  LevelSetBuildOptions o;
  o.dx = s.settings.dx;
  o.origin = s.settings.origin;
  o.band = int(ter.integer("band", 3, 1, 64));
  const double margin = 2 * kBlockDim * o.dx; // active blocks reach past the walls
  const Vec3d lo = s.settings.domain.min + s.settings.origin, hi = s.settings.domain.max + s.settings.origin;
  o.xmin = lo.x() - margin, o.ymin = lo.y() - margin, o.xmax = hi.x() + margin, o.ymax = hi.y() + margin;
  o.zmin = lo.z() - margin;
  o.sourcePath = dem.raw->sourcePath;
  o.smoothRadius = dem.smoothRadius;
  CachedLevelSet ls;
  try {
    ls = cachedDemLevelSet(*ground, o);
  } catch (const std::exception& e) {
    ter.fail(ter.has("dem") ? "dem" : "synthetic", std::string("cannot build the terrain level set: ") + e.what());
  }
  char buf[1024];
  if (ls.reused)
    std::snprintf(buf, sizeof buf, "terrain: %s; level set (dx %g m) reused from %s (read in %.2f s)",
                  dem.description.c_str(), o.dx, ls.path.c_str(), ls.loadSeconds);
  else
    std::snprintf(buf, sizeof buf, "terrain: %s; level set (dx %g m, %zu active voxels) built in %.2f s, cached in %s",
                  dem.description.c_str(), o.dx, ls.stats.activeVoxels, ls.stats.buildSeconds + ls.stats.writeSeconds,
                  ls.path.c_str());
  s.notes.push_back(buf);
  if (dem.filledCells > 0)
    s.notes.push_back("terrain: filled " + std::to_string(dem.filledCells) + " no-data cells of " + dem.raw->sourcePath);
  std::vector<std::shared_ptr<const Sdf>> parts{ls.sdf};
  for (const TerrainBody* b : bodies)
    if (auto solid = b->fixedSolid()) parts.push_back(solid);
  s.settings.terrain = parts.size() == 1 ? parts[0] : std::make_shared<UnionSdf>(parts);
  readTerrainLaw(ter, s.settings, dem.raw->grid.crsWkt);
  s.dem = ground;
}

void readMaterials(const ConfigTable& root, SceneSetup& s) {
  const auto tables = root.tables("materials");
  if (tables.empty()) root.fail("", "no [[materials]] given");
  for (size_t i = 0; i < tables.size(); ++i) {
    auto g = createMaterialGroup(*tables[i], int(i));
    // `basal = "sticky"` or `basal = { law = "coulomb", friction = 0.3 }`: this material's own law
    // at every collider (a string takes its parameters from basal_friction, ...).
    if (tables[i]->has("basal")) g->basalLaw = readContactLaw(*tables[i], "basal", "", "basal_", false);
    for (const auto& n : s.materialNames)
      if (n == g->name()) tables[i]->fail("name", "duplicate material name '" + n + "'");
    s.materialNames.push_back(g->name());
    s.materialModels.push_back(g->modelName());
    s.groups.push_back(std::move(g));
  }
}

MaterialGroup* findGroup(const ConfigTable& t, SceneSetup& s, std::string& name) {
  name = t.string("material");
  for (auto& g : s.groups)
    if (g->name() == name) return g.get();
  std::string list;
  for (const auto& n : s.materialNames) list += (list.empty() ? "" : ", ") + n;
  t.fail("material", "no material named '" + name + "' (materials: " + list + ")");
}

int groupPosition(const SceneSetup& s, const MaterialGroup* group) {
  for (size_t i = 0; i < s.groups.size(); ++i)
    if (s.groups[i].get() == group) return int(i);
  return -1;
}

/// The seeding of one body: the scene's, with the body's own particles_per_cell if it gives one
/// (more, lighter particles for a thin release: docs/convergence.md, "Thin releases").
SeedSpec bodySpec(const ConfigTable& t, SeedSpec spec) {
  spec.particlesPerCell = int(t.integer("particles_per_cell", spec.particlesPerCell, 1, 64));
  return spec;
}

/// Reads [[bodies]]: solids (`shape`) and terrain bodies (`kind`), builds the terrain they need,
/// then seeds them in order.
void readBodies(const ConfigTable& root, SceneSetup& s, const DemTerrainInput* dem, uint64_t seed, double jitter,
                bool jitterGiven) {
  const auto tables = root.tables("bodies");
  if (tables.empty()) root.fail("", "no [[bodies]] given: the scene has nothing to simulate");
  const Vec3d worldMin = s.settings.domain.min + s.settings.origin, worldMax = s.settings.domain.max + s.settings.origin;
  std::vector<std::unique_ptr<TerrainBody>> terrainBodies(tables.size());
  std::vector<const TerrainBody*> list;
  for (size_t i = 0; i < tables.size(); ++i) {
    const ConfigTable& t = *tables[i];
    const bool hasShape = t.has("shape"), hasKind = t.has("kind");
    if (hasShape && hasKind) t.fail("kind", "give either 'shape' (a solid body) or 'kind' (a terrain body), not both");
    if (!hasShape && !hasKind)
      t.fail("", "give 'shape' (box, sphere, cylinder) or 'kind' (release, layer, water, fixed)");
    if (!hasKind) continue;
    const std::string kind = t.choice("kind", "", {"release", "layer", "water", "fixed"});
    if (!dem) t.fail("kind", "terrain bodies need a DEM: [terrain] dem = \"file\" or synthetic = { ... }");
    terrainBodies[i] = std::make_unique<TerrainBody>(t, kind, *dem, s.settings.origin, worldMin, worldMax);
    list.push_back(terrainBodies[i].get());
  }
  std::shared_ptr<DemRaster> bed;
  try {
    if (dem) buildDemTerrain(*root.table("terrain"), *dem, list, s, bed);
    else readTerrain(root, s);
  } catch (const InputError& e) {
    if (e.located()) throw;
    root.table("terrain")->fail("", e.what()); // a limit: about the terrain
  }

  SeedSpec spec;
  spec.maxParticles = s.maxParticles;
  spec.dx = s.settings.dx;
  spec.particlesPerCell = s.particlesPerCell;
  spec.seed = seed;
  spec.jitter = jitter;
  spec.slice = &s.seedSlice;
  spec.terrain = s.settings.terrain.get();
  for (const auto& st : s.settings.structures) spec.solids.push_back(st.geometry.get());
  SeedSpec terrainSpec = spec;
  // A lattice cut by a sloping surface leaves terraces of particles; jitter breaks them up. Along
  // z only, with the lattice point deciding whether a sample is seeded: every lattice column
  // then keeps the lattice's count, so a layer's mass per plan area is uniform and so are its
  // maps (a lateral jitter moved particles across map cells: 5.8 % noise cell to cell on a
  // 30-degree slope, tests/test_map_uniformity.cpp). A body no lattice point falls in (thinner
  // than the spacing) is seeded by its jittered samples instead (io/scene/body_seeding.cpp).
  if (!jitterGiven) terrainSpec.jitter = 0.5;
  terrainSpec.verticalJitter = terrainSpec.latticeDecides = true;
  std::unique_ptr<HeightField> bedField;
  if (bed) bedField = std::make_unique<HeightField>(*bed);
  const DomainBox& dom = s.settings.domain;
  std::vector<const TerrainBody*> seeded;
  std::vector<HeldBody> held; // secondary releases
  for (size_t i = 0; i < tables.size(); ++i) {
    const ConfigTable& t = *tables[i];
    const std::string label = t.string("name", "bodies[" + std::to_string(i) + "]");
    if (const TerrainBody* tb = terrainBodies[i].get()) {
      std::string material;
      MaterialGroup* group = tb->kind() == TerrainBody::Kind::Fixed ? nullptr : findGroup(t, s, material);
      BodyReport rep;
      std::optional<ErodibleCover> cover;
      const size_t first = group ? group->particles.size() : 0;
      try {
        if (group && s.settings.terrain)
          cover = readErodibleCover(*tb, *bedField, s.settings.origin, s.settings.dx,
                                    bodySpec(t, terrainSpec).particlesPerCell, *group, groupPosition(s, group), seeded, rep);
        if (!cover)
          rep = seedTerrainBody(*tb, *bedField, bodySpec(t, terrainSpec), s.settings.origin, worldMin, worldMax, group,
                                seeded);
      } catch (const InputError& e) {
        if (e.located()) throw;
        t.fail("", e.what()); // a limit: about this body
      }
      rep.label = label;
      if (cover) { // a field under the flow, not particles: later bodies may overlap it
        s.notes.push_back(erodibleCoverNote(*cover, rep, s.settings.dx));
        s.settings.covers.push_back(std::move(*cover));
      } else {
        seeded.push_back(tb);
        if (std::string note = thinBodyNote(rep, s.settings.dx); !note.empty()) s.notes.push_back(note);
        if (group) holdSecondaryRelease(t, label, *group, groupPosition(s, group), first, held);
      }
      s.bodies.push_back(rep);
      continue;
    }
    std::string material;
    MaterialGroup* group = findGroup(t, s, material);
    auto shape = readBodyShape(t, s.settings.origin);
    BodyReport rep;
    const size_t first = group->particles.size();
    try {
      rep = seedShapeBody(t, *shape, bodySpec(t, spec), dom.min, dom.max, *group);
    } catch (const InputError& e) {
      if (e.located()) throw;
      t.fail("", e.what()); // a limit: about this body
    }
    rep.label = label;
    holdSecondaryRelease(t, label, *group, groupPosition(s, group), first, held);
    s.bodies.push_back(rep);
  }
  if (!held.empty()) s.settings.sources.push_back(std::make_shared<SecondaryReleases>(std::move(held), s.settings.dx));
}

void readOutput(const ConfigTable& root, SceneSetup& s) {
  s.output = readOutputSettings(root.table("output"), s.materialNames);
  // AvaFrame's simName parts: the release scenario, releases only or with covers, and a hash of
  // the whole configuration (AvaFrame hashes its configuration too), so runs differing in any
  // value have different names.
  PeakFileSettings& pf = s.output.maps.peakFiles;
  for (const auto& b : s.bodies)
    if (b.kind == "release") {
      pf.releaseName = b.label;
      break;
    }
  for (const auto& b : s.bodies)
    if (b.kind == "layer") pf.simType = "ent";
  if (dynamic_cast<const ResistedLaw*>(s.settings.terrainLaw.get())) // resistance areas: AvaFrame's res
    pf.simType = pf.simType == "ent" ? "entres" : "res";
  pf.simHash = fnv1aHex(root.canonicalText()).substr(0, 10);
  // The film: on by default where there is terrain to show it over, a hundred frames.
  AnimationSettings& an = s.output.maps.animation;
  an.enabled = an.requested.value_or(s.output.maps.enabled && s.settings.terrain != nullptr);
  if (!(an.interval > 0)) an.interval = s.endTime / 100;
}

} // namespace

SceneSetup buildScene(const ConfigTable& root, const SeedSlice& slice) {
  SceneSetup s;
  s.file = root.file();
  s.seedSlice.part = slice.part, s.seedSlice.parts = slice.parts;
  readSimulation(root, s);
  const ConfigTable* ter = root.table("terrain");
  std::optional<DemTerrainInput> dem;
  if (ter && isDemTerrain(*ter)) dem = readDemTerrain(*ter);
  readDomain(root, s, dem ? &*dem : nullptr);
  readMaterials(root, s);
  const ConfigTable* sim = root.table("simulation");
  const uint64_t seed = uint64_t(sim->integer("seed", 0, 0, INT64_MAX));
  const bool jitterGiven = sim->has("jitter");
  const double jitter = sim->inRange("jitter", 0, 0, 1);
  readStructures(root, s.settings, s.notes);
  readPanels(root, s.settings);
  readBodies(root, s, dem ? &*dem : nullptr, seed, jitter, jitterGiven);
  readInflows(root, s); // on the terrain the bodies built
  readOutput(root, s);
  s.ensemble = readEnsembleSettings(root.table("ensemble"),
                                    s.output.paths.empty() ? std::vector<Eigen::Vector2d>{} : s.output.paths[0].points);
  root.checkAllUsed();
  return s;
}

size_t SceneSetup::seededParticles() const {
  size_t n = 0;
  if (seedSlice.active())
    for (uint64_t c : seedSlice.seeded) n += c;
  else
    for (const auto& g : groups) n += g->size();
  return n;
}

RunContext SceneSetup::runContext() const {
  RunContext r;
  r.dx = settings.dx;
  r.endTime = endTime;
  r.particleSpacing = settings.dx / std::cbrt(double(particlesPerCell));
  r.origin = settings.origin;
  r.domainMin = settings.domain.min;
  r.domainMax = settings.domain.max;
  r.dem = dem;
  r.crsWkt = dem ? dem->grid.crsWkt : output.crsWkt;
  r.materialNames = materialNames;
  r.materialModels = materialModels;
  r.sceneKeys = keyLines;
  return r;
}

namespace {
/// The keys a resumed run may change: when it ends, and which frame files it writes how often.
/// Every other key (materials, bodies, terrain, laws, dx, particles per cell, and the outputs that
/// keep state in a checkpoint: series columns, maps) shapes the state a checkpoint holds.
bool resumeMayChange(const std::string& key) {
  static const char* const keys[] = {"simulation.end_time",     "output.directory", "output.frame_interval",
                                     "output.checkpoint_interval", "output.h5",        "output.vdb",
                                     "output.vdb_points",          "output.ply",       "output.plots", "output.report",
                                     "output.series_interval"};
  for (const char* k : keys)
    if (key == k) return true;
  return false;
}

/// The scene's keys after overrides, less those a resumed run may change.
std::string stateKeys(const ConfigTable& root) {
  std::string out;
  const std::string all = root.keyLines();
  for (size_t at = 0; at < all.size();) {
    const size_t end = all.find('\n', at);
    const std::string line = all.substr(at, end - at + 1);
    if (!resumeMayChange(line.substr(0, line.find(" = ")))) out += line;
    at = end + 1;
  }
  return out;
}

/// Overrides first, so `--set avaframe.release_thickness=2` reaches the AvaFrame folder's bodies.
SceneSetup build(ConfigTable& root, const std::vector<std::string>& overrides, const SeedSlice& slice) {
  for (const auto& o : overrides) applyOverride(root, o);
  std::vector<std::string> notes;
  expandAvaFrame(root, notes);
  SceneSetup s = buildScene(root, slice);
  s.notes.insert(s.notes.begin(), notes.begin(), notes.end());
  s.stateKeys = stateKeys(root);
  s.keyLines = root.keyLines();
  s.hash = fnv1aHex(s.stateKeys);
  return s;
}
} // namespace

SceneSetup loadSceneFile(const std::string& path, const std::vector<std::string>& overrides,
                         const SeedSlice& slice) {
  return build(*readTomlFile(path), overrides, slice);
}

SceneSetup loadSceneString(const std::string& text, const std::string& name,
                           const std::vector<std::string>& overrides, const SeedSlice& slice) {
  return build(*readTomlString(text, name), overrides, slice);
}

SceneSetup loadSceneTable(ConfigTable& root, const std::vector<std::string>& overrides, const SeedSlice& slice) {
  return build(root, overrides, slice);
}

} // namespace talus
