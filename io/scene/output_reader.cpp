#include "io/scene/output_reader.h"

#include "io/common/names.h"

#include "io/terrain/dem_raster.h"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace talus {

namespace {

/// `key = [[x, y], ...]`: at least two distinct points of world xy (m).
std::vector<Eigen::Vector2d> readPolyline(const ConfigTable& t, const std::string& key) {
  if (!t.has(key)) t.fail("", "missing required key '" + key + "'");
  const ConfigValue& v = t.values().at(key);
  const char* expected = "expected an array of [x, y] points, e.g. [[2600000, 1200000], [2600100, 1200000]]";
  if (!v.isArray()) t.fail(key, expected);
  std::vector<Eigen::Vector2d> pts;
  for (const auto& e : std::get<ConfigValue::Array>(v.data)) {
    if (!e.isArray()) t.fail(key, expected);
    const auto& xy = std::get<ConfigValue::Array>(e.data);
    if (xy.size() != 2 || !xy[0].isNumber() || !xy[1].isNumber()) t.fail(key, expected);
    const Eigen::Vector2d p(std::get<double>(xy[0].data), std::get<double>(xy[1].data));
    if (!p.allFinite()) t.fail(key, "must contain finite numbers");
    if (!pts.empty() && (p - pts.back()).norm() == 0) t.fail(key, "repeats a point");
    pts.push_back(p);
  }
  if (pts.size() < 2) t.fail(key, "needs at least two points");
  return pts;
}

/// `key = ["a", "b"]`, each a material name.
std::vector<std::string> readMaterialList(const ConfigTable& t, const std::string& key,
                                          const std::vector<std::string>& materialNames) {
  std::vector<std::string> out;
  if (!t.has(key)) return out;
  for (const std::string& n : t.strings(key)) {
    if (std::find(materialNames.begin(), materialNames.end(), n) == materialNames.end()) {
      std::string list;
      for (const auto& m : materialNames) list += (list.empty() ? "" : ", ") + m;
      t.fail(key, "no material named '" + n + "' (materials: " + list + ")");
    }
    if (std::find(out.begin(), out.end(), n) == out.end()) out.push_back(n);
  }
  return out;
}

/// `point = [x, y]` (or also [x, y, z] when `withZ`): finite world coordinates (m).
std::vector<double> readPoint(const ConfigTable& t, bool withZ, const char* expected) {
  const auto xyz = t.numbers("point");
  if (xyz.size() != 2 && !(withZ && xyz.size() == 3)) t.fail("point", expected);
  for (double v : xyz)
    if (!std::isfinite(v)) t.fail("point", "must contain finite numbers");
  return xyz;
}

/// Section and path names become CSV column and file names: keep them plain.
std::string readName(const ConfigTable& t, const std::string& fallback, std::vector<std::string>& used) {
  const std::string n = t.string("name", fallback);
  if (n.empty()) t.fail("name", "must not be empty");
  for (char c : n)
    if (!isSafeNameChar(c))
      t.fail("name", "'" + n + "': use letters, digits, '_', '-' or '.' (it names CSV columns)");
  if (std::find(used.begin(), used.end(), n) != used.end()) t.fail("name", "duplicate name '" + n + "'");
  used.push_back(n);
  return n;
}

void readMaps(const ConfigTable& out, const std::vector<std::string>& materialNames, MapSettings& m) {
  if (!out.has("maps")) return;
  const ConfigValue& v = out.values().at("maps");
  if (v.isBool()) {
    m.enabled = out.boolean("maps", false);
    return;
  }
  const ConfigTable* t = out.table("maps"); // fails with a clear message when neither bool nor table
  m.enabled = t->boolean("enabled", true);
  m.cellSize = t->positive("cell_size", 0);
  m.perMaterial = t->boolean("per_material", false);
  m.quicklook = t->boolean("quicklook", true);
  m.minHeight = t->positive("min_height", 0, true);
  m.minSpeed = t->positive("min_speed", 0, true);
  m.interval = t->positive("interval", 0, true);
  m.erodible = readMaterialList(*t, "erodible", materialNames);
  m.minErosionFraction = t->inRange("min_erosion_fraction", m.minErosionFraction, 0, 1);
}

/// `animation = true` or `animation = { interval, quantity, fps, max }` (docs/outputs.md).
void readAnimation(const ConfigTable& out, MapSettings& m) {
  if (!out.has("animation")) return;
  AnimationSettings& a = m.animation;
  if (out.values().at("animation").isBool()) {
    a.requested = out.boolean("animation", false);
  } else {
    const ConfigTable* t = out.table("animation");
    a.requested = t->boolean("enabled", true);
    a.interval = t->positive("interval", 0, true);
    a.quantity = t->choice("quantity", a.quantity, {"thickness", "speed"});
    a.fps = int(t->integer("fps", a.fps, 1, 120));
    a.scaleMax = t->positive("max", 0, true);
  }
  if (*a.requested && !m.enabled)
    out.fail("animation", "the animation is drawn from rasters the hazard maps record: it needs maps = true");
}

} // namespace

OutputSettings readOutputSettings(const ConfigTable* out, const std::vector<std::string>& materialNames) {
  OutputSettings s;
  if (!out) return s;
  s.directory = out->string("directory", s.directory);
  s.frameInterval = out->positive("frame_interval", 0, true);
  if (out->has("crs")) {
    try {
      s.crsWkt = crsToWkt(out->string("crs"));
    } catch (const std::exception& e) {
      out->fail("crs", e.what());
    }
  }
  s.h5Frames = out->boolean("h5", s.h5Frames);
  s.vdb = out->boolean("vdb", s.vdb);
  s.vdbPoints = out->boolean("vdb_points", s.vdbPoints);
  s.ply = out->boolean("ply", s.ply);
  s.series = out->boolean("series", s.series);
  s.seriesInterval = out->positive("series_interval", 0, true);
  s.checkpointInterval = out->has("checkpoint_interval") ? out->positive("checkpoint_interval", 0, true) : -1.0;
  s.plots = out->boolean("plots", s.plots);
  s.report = out->boolean("report", s.report);
  s.loads = out->boolean("loads", s.loads);
  s.waterMaterials = readMaterialList(*out, "water_materials", materialNames);
  readMaps(*out, materialNames, s.maps);
  s.maps.peakFiles.enabled = out->boolean("peak_files", false);
  if (out->has("peak_file_format")) s.maps.peakFiles.format = out->choice("peak_file_format", "", {"asc", "tif", "both"});
  s.maps.peakFiles.grid = out->choice("peak_file_grid", "dem", {"dem", "com1dfa"});
  s.maps.peakFiles.meshCellSize = out->positive("peak_file_cell_size", 5.0);
  if (s.maps.peakFiles.enabled && !s.maps.enabled)
    out->fail("peak_files", "AvaFrame peak files are written from the hazard maps: they need maps = true");
  readAnimation(*out, s.maps);

  std::vector<std::string> used;
  const auto sections = out->tables("sections");
  for (size_t i = 0; i < sections.size(); ++i) {
    const ConfigTable& t = *sections[i];
    SectionSpec sec;
    sec.name = readName(t, "section" + std::to_string(i), used);
    sec.points = readPolyline(t, "points");
    sec.zMin = t.number("z_min", sec.zMin);
    sec.zMax = t.number("z_max", sec.zMax);
    if (!(sec.zMax > sec.zMin)) t.fail("z_max", "must exceed z_min");
    s.sections.push_back(sec);
  }
  used.clear();
  const auto paths = out->tables("paths");
  for (size_t i = 0; i < paths.size(); ++i) {
    const ConfigTable& t = *paths[i];
    PathSpec p;
    p.name = readName(t, "path" + std::to_string(i), used);
    p.points = readPolyline(t, "points");
    p.threshold = t.positive("threshold", 0);
    p.halfWidth = t.positive("half_width", 0, true);
    p.minSpeed = t.positive("min_speed", 0, true);
    p.materials = readMaterialList(t, "materials", materialNames);
    s.paths.push_back(p);
  }
  used.clear();
  const auto probes = out->tables("probes");
  for (size_t i = 0; i < probes.size(); ++i) {
    const ConfigTable& t = *probes[i];
    ProbeSpec p;
    p.name = readName(t, "probe" + std::to_string(i), used);
    const auto xyz = readPoint(t, true, "expected [x, y] (start at the material's mean height there) or [x, y, z] (m)");
    p.hasZ = xyz.size() == 3;
    p.point = Eigen::Vector3d(xyz[0], xyz[1], p.hasZ ? xyz[2] : 0.0);
    p.radius = t.positive("radius", 0);
    p.materials = readMaterialList(t, "materials", materialNames);
    s.probes.push_back(p);
  }
  used.clear();
  const auto gauges = out->tables("gauges");
  for (size_t i = 0; i < gauges.size(); ++i) {
    const ConfigTable& t = *gauges[i];
    GaugeSpec g;
    g.name = readName(t, "gauge" + std::to_string(i), used);
    const auto xy = readPoint(t, false, "expected [x, y], the gauge's position in world coordinates (m)");
    g.point = Eigen::Vector2d(xy[0], xy[1]);
    g.radius = t.positive("radius", 0);
    s.gauges.push_back(g);
  }
  if ((!s.sections.empty() || !s.paths.empty() || !s.probes.empty() || !s.gauges.empty()) && !s.series)
    out->fail("series", "sections, paths, probes and gauges are columns of series.csv: they need series = true");
  return s;
}

} // namespace talus
