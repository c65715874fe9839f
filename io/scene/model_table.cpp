#include "io/scene/model_table.h"

#include "io/scene/material_presets.h"
#include "materials/cam_clay.h"
#include "materials/drucker_prager.h"
#include "materials/elastic.h"
#include "materials/fluid_group.h"
#include "materials/mu_i.h"
#include "materials/solid_group.h"

#include <cmath>
#include <limits>
#include <optional>

namespace talus {

namespace {

constexpr double kInf = std::numeric_limits<double>::infinity();

/// Reads a material's keys: the table's value when given, else the preset's, else a default
/// (or an error when there is none). Every value is range-checked with the key's line.
class MaterialReader {
public:
  MaterialReader(const ConfigTable& t, const MaterialPreset* preset) : t_(t), preset_(preset) {}

  double get(const std::string& key, std::optional<double> fallback, double lo, double hi, bool openLo,
             bool openHi) const {
    if (t_.has(key)) return t_.inRange(key, 0, lo, hi, openLo, openHi);
    if (preset_) {
      auto it = preset_->values.find(key);
      if (it != preset_->values.end()) return it->second;
    }
    if (!fallback) t_.missing(key);
    return *fallback;
  }
  double positive(const std::string& key, std::optional<double> fallback = std::nullopt) const {
    if (t_.has(key)) return t_.positive(key);
    return get(key, fallback, 0, kInf, true, true);
  }
  double nonNegative(const std::string& key, std::optional<double> fallback) const {
    if (t_.has(key)) return t_.positive(key, 0, true);
    return get(key, fallback, 0, kInf, false, true);
  }
  /// Angle in degrees, strictly inside (0, 90); returned in radians.
  double angle(const std::string& key, std::optional<double> fallback = std::nullopt) const {
    return get(key, fallback, 0, 90, true, true) * M_PI / 180.0;
  }
  const ConfigTable& table() const { return t_; }

private:
  const ConfigTable& t_;
  const MaterialPreset* preset_;
};

/// What every group constructor receives besides its model.
struct GroupHead {
  std::string name;
  int index;
  double density;
};

HenckyElasticity readElasticity(const MaterialReader& r) {
  const double scale = r.positive("elastic_scale", 1.0);
  const double E = r.positive("youngs_modulus") * scale;
  const double nu = r.get("poisson_ratio", 0.3, -1.0, 0.5, true, true);
  return HenckyElasticity::fromYoung(E, nu);
}

std::unique_ptr<MaterialGroup> buildElastic(const MaterialReader& r, const GroupHead& h) {
  ElasticModel m;
  m.elastic = readElasticity(r);
  return std::make_unique<SolidGroup<ElasticModel>>(h.name, h.index, h.density, m);
}

std::unique_ptr<MaterialGroup> buildDruckerPrager(const MaterialReader& r, const GroupHead& h) {
  const HenckyElasticity e = readElasticity(r);
  DruckerPragerParams p;
  p.frictionAngle = r.angle("friction_angle");
  p.residualFrictionAngle = r.angle("residual_friction_angle", p.frictionAngle * 180 / M_PI);
  p.cohesion = r.nonNegative("cohesion", 0.0);
  p.softening = r.nonNegative("softening", 0.0);
  const std::string cone = r.table().choice("cone", "compression", {"compression", "plane_strain", "extension"});
  p.cone = cone == "plane_strain" ? DruckerPragerCone::PlaneStrain
           : cone == "extension"  ? DruckerPragerCone::Extension
                                  : DruckerPragerCone::Compression;
  return std::make_unique<SolidGroup<DruckerPragerModel>>(h.name, h.index, h.density, DruckerPragerModel(e, p));
}

std::unique_ptr<MaterialGroup> buildMuI(const MaterialReader& r, const GroupHead& h) {
  MuIModel m;
  m.elastic = readElasticity(r);
  m.params.muS = r.positive("mu_s", m.params.muS);
  m.params.mu2 = r.positive("mu_2", m.params.mu2);
  if (m.params.mu2 <= m.params.muS) r.table().fail("mu_2", "mu_2 must exceed mu_s (" + std::to_string(m.params.muS) + ")");
  m.params.i0 = r.positive("i0", m.params.i0);
  m.params.grainDiameter = r.positive("grain_diameter", m.params.grainDiameter);
  m.params.grainDensity = r.positive("grain_density", m.params.grainDensity);
  return std::make_unique<SolidGroup<MuIModel>>(h.name, h.index, h.density, m);
}

std::unique_ptr<MaterialGroup> buildCamClay(const MaterialReader& r, const GroupHead& h) {
  CamClayModel m;
  m.elastic = readElasticity(r);
  m.params.M = r.positive("critical_state_slope");
  m.params.Ms = r.positive("critical_state_slope_flowing", m.params.M);
  m.params.p0 = r.positive("preconsolidation_pressure");
  m.params.beta = r.nonNegative("tension_ratio", 0.0);
  m.params.xi = r.positive("hardening");
  auto g = std::make_unique<SolidGroup<CamClayModel>>(h.name, h.index, h.density, m);
  g->initialState.set(m.initialVolumetricStrain(), false);
  return g;
}

std::unique_ptr<MaterialGroup> buildWater(const MaterialReader& r, const GroupHead& h) {
  const ConfigTable& t = r.table();
  TaitWaterModel m;
  m.exponent = r.get("tait_exponent", 7.0, 1.0, 20.0, false, false);
  if (t.has("sound_speed")) {
    if (t.has("bulk_modulus")) t.fail("sound_speed", "give either bulk_modulus or sound_speed, not both");
    const double c = t.positive("sound_speed");
    m.bulk = h.density * c * c / m.exponent; // c^2 = k B / rho0
  } else {
    m.bulk = r.positive("bulk_modulus");
  }
  m.viscosity = r.nonNegative("viscosity", 0.0);
  m.maxTension = r.get("max_tension", 0.0, 0, m.bulk, false, true);
  m.smoothPressure = t.boolean("smooth_pressure", false);
  auto g = std::make_unique<FluidGroup>(h.name, h.index, h.density, m);
  g->hydrostatic = t.boolean("hydrostatic", true);
  return g;
}

struct ModelRow {
  const char* name;
  std::unique_ptr<MaterialGroup> (*build)(const MaterialReader&, const GroupHead&);
};

const std::vector<ModelRow>& modelTable() {
  static const std::vector<ModelRow> rows{
      {ElasticModel::kName, buildElastic},
      {DruckerPragerModel::kName, buildDruckerPrager},
      {MuIModel::kName, buildMuI},
      {CamClayModel::kName, buildCamClay},
      {TaitWaterModel::kName, buildWater},
  };
  return rows;
}

} // namespace

std::vector<std::string> materialModelNames() {
  std::vector<std::string> names;
  for (const auto& row : modelTable()) names.push_back(row.name);
  return names;
}

std::unique_ptr<MaterialGroup> createMaterialGroup(const ConfigTable& t, int index) {
  const std::string name = t.string("name");
  const MaterialPreset* preset = nullptr;
  if (t.has("preset")) {
    std::vector<std::string> names;
    for (const auto& [n, p] : materialPresets()) names.push_back(n);
    preset = &materialPresets().at(t.choice("preset", "", names));
  }
  std::string model;
  if (t.has("model")) {
    model = t.choice("model", "", materialModelNames());
    if (preset && preset->model != model)
      t.fail("model", "preset '" + t.string("preset") + "' is a '" + preset->model + "' material, not '" + model + "'");
  } else if (preset) {
    model = preset->model;
  } else {
    t.fail("", "missing required key 'model' (or a 'preset')");
  }
  const MaterialReader r(t, preset);
  const GroupHead head{name, index, r.positive("density")};
  for (const auto& row : modelTable())
    if (model == row.name) return row.build(r, head);
  // A preset naming a model the table lacks: a defect of the preset table, said plainly.
  t.fail("preset", "preset model '" + model + "' is not in the model table");
}

} // namespace talus
