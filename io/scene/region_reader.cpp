#include "io/scene/region_reader.h"

#include "engine/detrainment.h"
#include "engine/resistance_law.h"
#include "io/scene/contact_law_table.h"
#include "io/terrain/dem_raster.h"
#include "io/terrain/polygon_set.h"
#include "io/terrain/terrain_loader.h"

#include <algorithm>
#include <cmath>

namespace talus {

namespace {

struct Layer {
  // A polygon layer sets `values` (parameter index, value) inside `polygons`; a raster layer sets
  // parameter `index` from `grid`/`data` where the raster covers.
  PolygonSet polygons;
  std::vector<std::pair<int, float>> values;
  bool raster = false;
  int index = 0;
  RasterGrid grid;
  std::vector<float> data;
};

class RegionField final : public ParameterField {
public:
  RegionField(std::vector<float> defaults, std::vector<Layer> layers, const Vec3d& origin, double dx)
      : defaults_(std::move(defaults)), layers_(std::move(layers)), origin_(origin), dx_(dx) {}
  int count() const override { return int(defaults_.size()); }
  void sample(const Vec3d& x, float* out) const override {
    std::copy(defaults_.begin(), defaults_.end(), out);
    const double wx = x.x() + origin_.x(), wy = x.y() + origin_.y();
    for (const Layer& l : layers_) {
      if (l.raster) {
        int c, r;
        if (l.grid.locate(wx, wy, c, r)) out[l.index] = float(sampleBilinear(l.grid, l.data, wx, wy));
      } else {
        // A node stands for its cell: the polygon's value weighted by the part of the cell it
        // covers (4 x 4 samples), so a boundary through a node is not all on one side.
        int in = 0;
        for (int a = 0; a < 4; ++a)
          for (int b = 0; b < 4; ++b) in += l.polygons.contains(wx + (a - 1.5) * dx_ / 4, wy + (b - 1.5) * dx_ / 4);
        const float f = float(in) / 16.f;
        if (in)
          for (const auto& [i, v] : l.values) out[i] = (1 - f) * out[i] + f * v;
      }
    }
  }

private:
  std::vector<float> defaults_;
  std::vector<Layer> layers_;
  Vec3d origin_;
  double dx_;
};

int parameterIndex(const ConfigTable& t, const std::string& key, const std::vector<std::string>& names,
                   const ContactLaw& law) {
  const auto it = std::find(names.begin(), names.end(), key);
  if (it != names.end()) return int(it - names.begin());
  std::string list;
  for (const auto& n : names) list += (list.empty() ? "" : ", ") + n;
  t.fail(key, std::string("the terrain law '") + law.name() + "' has no parameter '" + key + "' (its parameters: " + list + ")");
}

void checkCrs(const ConfigTable& t, const std::string& key, const std::string& fileCrs, const std::string& demCrs) {
  if (!sameCrs(fileCrs, demCrs))
    t.fail(key, "its CRS " + crsName(fileCrs) + " is not the terrain's (" + crsName(demCrs) + "); reproject it");
}

Layer readRaster(const ConfigTable& t, const std::vector<std::string>& names, const ContactLaw& law,
                 const SimulationSettings& s, const std::string& demCrs) {
  Layer l;
  l.raster = true;
  l.index = parameterIndex(t, t.string("parameter"), names, law);
  const std::string file = resolveScenePath(t.file(), t.string("raster"));
  DemRaster r;
  try {
    DemReadOptions o;
    o.keepNodata = true;
    r = readDem(file, o);
  } catch (const InputError& e) {
    t.fail("raster", e.what());
  }
  checkCrs(t, "raster", r.grid.crsWkt, demCrs);
  // Only the cells over the domain matter: none there is an error, as is no-data or a negative
  // value there (the law would get no value, or a meaningless one, where the flow may go).
  const Vec3d lo = s.domain.min + s.origin, hi = s.domain.max + s.origin;
  size_t inside = 0, nodata = 0, negative = 0;
  for (int row = 0; row < r.grid.ny; ++row)
    for (int col = 0; col < r.grid.nx; ++col) {
      const double x = r.grid.cellCentreX(col), y = r.grid.cellCentreY(row);
      if (x < lo.x() || x > hi.x() || y < lo.y() || y > hi.y()) continue;
      ++inside;
      const float v = r.height[r.grid.index(col, row)];
      nodata += std::isnan(v);
      negative += v < 0;
    }
  if (!inside) t.fail("raster", file + " does not overlap the domain");
  if (nodata) t.fail("raster", file + " has " + std::to_string(nodata) + " no-data cells inside the domain; fill them");
  if (negative) t.fail("raster", file + " has " + std::to_string(negative) + " negative values inside the domain");
  l.grid = r.grid;
  l.data = std::move(r.height);
  return l;
}

Layer readPolygons(const ConfigTable& t, const std::vector<std::string>& names, const ContactLaw& law,
                   const std::string& demCrs) {
  Layer l;
  const std::string file = resolveScenePath(t.file(), t.string("polygon"));
  try {
    l.polygons = PolygonSet::read(file, "", t.string("polygon_layer", ""));
  } catch (const InputError& e) {
    t.fail("polygon", e.what());
  }
  checkCrs(t, "polygon", l.polygons.crsWkt(), demCrs);
  for (const auto& [key, value] : t.values()) {
    if (key == "polygon" || key == "polygon_layer") continue;
    const int i = parameterIndex(t, key, names, law);
    l.values.push_back({i, float(t.positive(key, 0, true))});
  }
  if (l.values.empty()) t.fail("polygon", "give the law's parameters inside it, e.g. friction = 0.3");
  // A forest detrains as AvaFrame's does by default (detK 5 Pa) unless the region says otherwise.
  if (const auto* r = dynamic_cast<const ResistedLaw*>(&law); r && t.has("resistance") && !t.has("detrainment"))
    l.values.push_back({r->detrainmentIndex(), float(ResistedLaw::kDetrainment)});
  return l;
}

} // namespace

std::shared_ptr<const ParameterField> readTerrainRegions(const ConfigTable& terrain, const ContactLaw& law,
                                                         const SimulationSettings& settings, const std::string& demCrs) {
  const auto tables = terrain.tables("regions");
  if (tables.empty()) return nullptr;
  const std::vector<std::string> names = law.parameterNames();
  if (names.empty())
    terrain.fail("regions", std::string("the terrain law '") + law.name() + "' has no parameters to vary by region");
  std::vector<Layer> layers;
  for (const ConfigTable* t : tables) {
    if (t->has("raster") == t->has("polygon")) t->fail("", "give either 'raster' (with 'parameter') or 'polygon'");
    layers.push_back(t->has("raster") ? readRaster(*t, names, law, settings, demCrs)
                                      : readPolygons(*t, names, law, demCrs));
  }
  std::vector<float> defaults;
  for (double v : law.parameterValues()) defaults.push_back(float(v));
  return std::make_shared<RegionField>(std::move(defaults), std::move(layers), settings.origin, settings.dx);
}

void readTerrainLaw(const ConfigTable& terrain, SimulationSettings& settings, const std::string& demCrs) {
  settings.terrainLaw = readContactLaw(terrain, "boundary", "friction", "", false);
  for (const ConfigTable* t : terrain.tables("regions"))
    if (t->has("resistance")) {
      settings.terrainLaw = std::make_shared<ResistedLaw>(settings.terrainLaw);
      break;
    }
  settings.terrainParameters = readTerrainRegions(terrain, *settings.terrainLaw, settings, demCrs);
  const auto* resisted = dynamic_cast<const ResistedLaw*>(settings.terrainLaw.get());
  if (!resisted) return;
  bool detrains = false; // a forest that detrains anywhere: the phase runs (engine/detrainment.h)
  for (const ConfigTable* t : terrain.tables("regions"))
    detrains |= (t->has("resistance") && !t->has("detrainment")) || (t->has("detrainment") && t->number("detrainment") > 0) ||
                t->string("parameter", "") == "detrainment";
  if (detrains)
    settings.sources.push_back(std::make_shared<Detrainment>(settings.terrainParameters, resisted->resistanceIndex(),
                                                             resisted->detrainmentIndex(), settings.dx));
}

} // namespace talus
