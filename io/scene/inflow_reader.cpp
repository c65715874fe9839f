#include "io/scene/inflow_reader.h"

#include "engine/inflow_source.h"
#include "io/common/input_error.h"
#include "io/terrain/terrain_loader.h"

#include <cmath>
#include <fstream>
#include <sstream>

namespace talus {

namespace {

std::vector<double> numbersOf(const ConfigValue& v) {
  std::vector<double> out;
  if (!v.isArray()) return out;
  for (const auto& e : std::get<ConfigValue::Array>(v.data))
    if (e.isNumber()) out.push_back(std::get<double>(e.data));
    else return {};
  return out;
}

/// Rows of (t, Q[, v]) from the table's `hydrograph`: a CSV file or an inline array.
std::vector<std::vector<double>> hydrographRows(const ConfigTable& t) {
  std::vector<std::vector<double>> rows;
  const ConfigValue& h = t.values().at("hydrograph");
  if (h.isArray()) {
    for (const auto& r : std::get<ConfigValue::Array>(h.data)) {
      rows.push_back(numbersOf(r));
      if (rows.back().size() < 2 || rows.back().size() > 3) t.fail("hydrograph", "expected [[t, Q], ...] or [[t, Q, v], ...]");
    }
    return rows;
  }
  const std::string file = resolveScenePath(t.file(), t.string("hydrograph"));
  std::ifstream in(file);
  if (!in) t.fail("hydrograph", "cannot read " + file);
  std::string line;
  std::getline(in, line); // the header: time_s, discharge_m3_s[, speed_m_s]
  for (int no = 2; std::getline(in, line); ++no) {
    if (line.find_first_not_of(" \t\r") == std::string::npos) continue;
    std::vector<double> r;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) {
      char* end = nullptr;
      const double v = std::strtod(cell.c_str(), &end);
      while (end && (*end == ' ' || *end == '\t' || *end == '\r')) ++end;
      if (end == cell.c_str() || (end && *end) || !std::isfinite(v))
        throw InputError(file, no, "", "'" + cell + "' is not a number (rows: time_s, discharge_m3_s[, speed_m_s])");
      r.push_back(v);
    }
    if (r.size() < 2 || r.size() > 3) throw InputError(file, no, "", "expected 2 or 3 columns: time_s, discharge_m3_s[, speed_m_s]");
    rows.push_back(r);
  }
  return rows;
}

/// Ground elevation (local z) below (x, y): the terrain's zero crossing, marched down from the
/// domain's top by its distance; the domain's floor without terrain.
double groundBelow(const SimulationSettings& s, double x, double y) {
  if (!s.terrain) return s.domain.min.z();
  double z = s.domain.max.z();
  for (int i = 0; i < 10000 && z > s.domain.min.z(); ++i) {
    const double d = s.terrain->distance(Vec3d(x, y, z));
    if (d < 1e-3 * s.dx) break;
    z -= std::max(d, 1e-3 * s.dx);
  }
  return std::max(z, s.domain.min.z());
}

} // namespace

void readInflows(const ConfigTable& root, SceneSetup& s) {
  const auto tables = root.tables("inflows");
  for (size_t i = 0; i < tables.size(); ++i) {
    const ConfigTable& t = *tables[i];
    InflowSpec spec;
    spec.name = t.string("name", "inflows[" + std::to_string(i) + "]");
    const std::string material = t.string("material");
    for (size_t g = 0; g < s.groups.size(); ++g)
      if (s.groups[g]->name() == material) spec.group = int(g), spec.density = s.groups[g]->density();
    if (spec.group < 0) t.fail("material", "no material named '" + material + "'");
    const auto section = t.has("section") ? std::get_if<ConfigValue::Array>(&t.values().at("section").data) : nullptr;
    if (!section || section->size() != 2 || numbersOf((*section)[0]).size() != 2 || numbersOf((*section)[1]).size() != 2)
      t.fail("section", "expected [[x0, y0], [x1, y1]] (world), across the channel");
    const auto p0 = numbersOf((*section)[0]), p1 = numbersOf((*section)[1]);
    spec.a = Vec3d(p0[0], p0[1], 0) - s.settings.origin, spec.b = Vec3d(p1[0], p1[1], 0) - s.settings.origin;
    spec.a.z() = spec.b.z() = 0;
    spec.spacing = s.settings.dx / std::cbrt(double(s.particlesPerCell));
    const Vec3d along = spec.b - spec.a;
    const size_t slots = size_t(std::floor(along.norm() / spec.spacing + 1e-9)); // a whole number stays whole
    if (slots == 0) t.fail("section", "shorter than a particle spacing (" + std::to_string(spec.spacing) + " m)");
    spec.direction = Vec3d(-along.y(), along.x(), 0).normalized(); // its left
    if (t.has("direction")) {
      const auto d = t.numbers("direction");
      if (d.size() != 2 || !(std::hypot(d[0], d[1]) > 0)) t.fail("direction", "expected [dx, dy], not zero");
      spec.direction = Vec3d(d[0], d[1], 0).normalized();
    }
    if (!t.has("hydrograph")) t.fail("hydrograph", "give a CSV file (time_s, discharge_m3_s[, speed_m_s]) or [[t, Q], ...]");
    const auto rows = hydrographRows(t);
    const double speed = t.positive("speed", 0, true);
    for (const auto& r : rows) {
      spec.time.push_back(r[0]), spec.discharge.push_back(r[1]);
      spec.speed.push_back(r.size() == 3 ? r[2] : speed);
    }
    for (size_t k = 0; k < slots; ++k) {
      const Vec3d at = spec.a + (double(k) + 0.5) * spec.spacing * along.normalized();
      spec.ground.push_back(groundBelow(s.settings, at.x(), at.y()));
    }
    try {
      s.settings.sources.push_back(std::make_shared<InflowSource>(std::move(spec)));
    } catch (const std::invalid_argument& e) {
      t.fail(rows.empty() || rows[0].size() == 3 || t.has("speed") ? "hydrograph" : "speed", e.what());
    }
  }
}

} // namespace talus
