#include "io/scene/structure_reader.h"

#include "engine/dam_sdf.h"
#include "engine/sdf_solids.h"
#include "io/scene/contact_law_table.h"
#include "io/terrain/line_features.h"
#include "io/terrain/shape_reader.h"
#include "io/terrain/terrain_loader.h"
#include "io/terrain/vdb_level_set.h"

#include <algorithm>
#include <cmath>
#include <filesystem>

namespace talus {

namespace {

/// Depth of the deepest point inside the solid (its half thickness), sampled on a lattice.
double halfThickness(const Shape& shape, double dx) {
  Vec3d lo, hi;
  shape.bounds(lo, hi);
  const double h = std::max(0.5 * dx, (hi - lo).maxCoeff() / 64);
  double deepest = 0;
  for (double x = lo.x(); x <= hi.x(); x += h)
    for (double y = lo.y(); y <= hi.y(); y += h)
      for (double z = lo.z(); z <= hi.z(); z += h) deepest = std::max(deepest, -shape.distance(Vec3d(x, y, z)));
  return deepest;
}

/// shape = "dam": `line = [[x, y, crest], ...]` (world) or `line_file` (a vector file whose line
/// vertices carry the crest as z: AvaFrame's DAM/), `slope` (degrees; default the file's `slope`
/// attribute), `crest_width` (m, default dx). Down to below the domain: the terrain hides the base.
std::shared_ptr<const Sdf> readDam(const ConfigTable& t, const SimulationSettings& s, const std::string& label) {
  if (t.has("line") == t.has("line_file")) t.fail("line", "give either 'line' ([[x, y, crest], ...]) or 'line_file'");
  std::vector<LineFeature> lines;
  if (t.has("line_file")) {
    lines = readLineFeatures(resolveScenePath(t.file(), t.string("line_file")), "slope");
  } else {
    const auto& arr = std::get<ConfigValue::Array>(t.values().at("line").data);
    LineFeature f;
    for (size_t i = 0; i < arr.size(); ++i) {
      if (!arr[i].isArray() || std::get<ConfigValue::Array>(arr[i].data).size() != 3)
        t.fail("line", "expected [[x, y, crest], ...]: three numbers per vertex");
      const auto& v = std::get<ConfigValue::Array>(arr[i].data);
      for (const auto& c : v)
        if (!c.isNumber()) t.fail("line", "expected [[x, y, crest], ...]: three numbers per vertex");
      f.points.emplace_back(std::get<double>(v[0].data), std::get<double>(v[1].data), std::get<double>(v[2].data));
    }
    lines.push_back(f);
  }
  const double width = t.positive("crest_width", s.dx, true);
  const double base = s.domain.min.z() - s.dx; // below the domain: the terrain hides the dam's base
  std::vector<std::shared_ptr<const Sdf>> parts;
  for (size_t k = 0; k < lines.size(); ++k) {
    const double slope = t.has("slope") ? t.inRange("slope", 60, 0, 90, true) : lines[k].value;
    if (!(slope > 0 && slope <= 90)) t.fail("slope", "give the dam's flank slope in degrees (0, 90] (the line file has none)");
    std::vector<DamSdf::Vertex> v;
    for (const auto& p : lines[k].points) {
      if (!std::isfinite(p.z())) t.fail("line_file", "the line's vertices carry no elevation (the crest, as z)");
      v.push_back({p.x() - s.origin.x(), p.y() - s.origin.y(), p.z() - s.origin.z(), base});
    }
    try {
      parts.push_back(std::make_shared<DamSdf>(v, slope, width, "dam '" + label + "'"));
    } catch (const std::invalid_argument& e) {
      t.fail(t.has("line") ? "line" : "line_file", e.what());
    }
  }
  return parts.size() == 1 ? parts[0] : std::make_shared<UnionSdf>(parts);
}

std::shared_ptr<const Sdf> readGeometry(const ConfigTable& t, const SimulationSettings& s, std::vector<std::string>& notes,
                                        const std::string& label) {
  const std::string kind = t.choice("shape", "", {"box", "cylinder", "sphere", "level_set", "dam"});
  if (kind == "dam") return readDam(t, s, label);
  if (kind == "level_set") {
    const std::string file = resolveScenePath(t.file(), t.string("file"));
    if (!std::filesystem::is_regular_file(file)) t.fail("file", "file not found: " + file);
    try {
      return std::make_shared<VdbLevelSet>(file, t.string("grid", ""), s.origin);
    } catch (const std::exception& e) {
      t.fail("file", file + ": " + e.what());
    }
  }
  if (t.has("file")) t.fail("file", "only shape = \"level_set\" reads a file");
  std::shared_ptr<const Shape> shape = readBodyShape(t, s.origin);
  // Contact is decided at grid nodes: a wall thinner than about two cells lets material through.
  if (halfThickness(*shape, s.dx) < s.dx)
    notes.push_back("structure '" + label + "' is thinner than two grid cells (dx " + std::to_string(s.dx) +
                    " m): material may pass through it between nodes");
  return std::make_shared<ShapeSdf>(shape, kind + " '" + label + "'");
}

} // namespace

void readStructures(const ConfigTable& root, SimulationSettings& s, std::vector<std::string>& notes) {
  const auto tables = root.tables("structures");
  for (size_t i = 0; i < tables.size(); ++i) {
    const ConfigTable& t = *tables[i];
    StructureSpec spec;
    spec.name = t.string("name", "structures[" + std::to_string(i) + "]");
    for (const auto& other : s.structures)
      if (other.name == spec.name) t.fail("name", "duplicate structure name '" + spec.name + "'");
    for (const char* face : faceNames())
      if (spec.name == face || spec.name == "terrain")
        t.fail("name", "'" + spec.name + "' names a domain face or the terrain; choose another name");
    spec.geometry = readGeometry(t, s, notes, spec.name);
    spec.law = readContactLaw(t, "law", "slip", "", false);
    Vec3d lo, hi;
    spec.geometry->bounds(lo, hi);
    const Vec3d centre = lo.allFinite() && hi.allFinite() ? Vec3d(0.5 * (lo + hi)) : Vec3d::Zero();
    spec.motion.pivot = centre;
    if (const ConfigTable* m = t.table("motion")) {
      spec.motion.velocity = m->vec3("velocity", Vec3d::Zero());
      spec.motion.angularVelocity = m->vec3("angular_velocity", Vec3d::Zero());
      if (m->has("pivot")) spec.motion.pivot = m->vec3("pivot") - s.origin;
      spec.motion.start = m->number("start", 0.0);
      spec.motion.stop = m->number("stop", std::numeric_limits<double>::infinity());
      if (!(spec.motion.stop > spec.motion.start)) m->fail("stop", "must be later than start");
    }
    spec.momentPoint = t.has("moment_point") ? Vec3d(t.vec3("moment_point") - s.origin) : centre;
    s.structures.push_back(std::move(spec));
  }
}

void readPanels(const ConfigTable& root, SimulationSettings& s) {
  const auto tables = root.tables("panels");
  for (size_t i = 0; i < tables.size(); ++i) {
    const ConfigTable& t = *tables[i];
    PanelSpec p;
    p.name = t.string("name", "panels[" + std::to_string(i) + "]");
    bool taken = p.name == "terrain";
    for (const char* face : faceNames()) taken |= p.name == face;
    for (const auto& other : s.structures) taken |= other.name == p.name;
    for (const auto& other : s.panels) taken |= other.name == p.name;
    if (taken) t.fail("name", "'" + p.name + "' already names a collider (the terrain, a face, a structure or a panel)");
    const std::string face = t.choice("face", "", {faceNames().begin(), faceNames().end()});
    p.face = int(std::find_if(faceNames().begin(), faceNames().end(), [&](const char* f) { return face == f; }) -
                 faceNames().begin());
    if (!s.faces[size_t(p.face)])
      t.fail("face", face + " is open or periodic: a panel needs a closed face to be part of");
    p.lo = t.vec3("min") - s.origin, p.hi = t.vec3("max") - s.origin;
    // The panel holds the face's nodes inside it: at least one along each in-plane axis.
    for (int a = 0; a < 3; ++a)
      if (a != p.face / 2 && std::ceil(p.lo[a] / s.dx - 1e-6) > std::floor(p.hi[a] / s.dx + 1e-6))
        t.fail("max", std::string("the panel holds no grid node along ") + "xyz"[a] + " (dx " + std::to_string(s.dx) +
                          " m): make it reach a node plane or widen it");
    s.panels.push_back(std::move(p));
  }
}

} // namespace talus
