#include "materials/material_factory.h"

#include "materials/elastic.h"
#include "materials/solid_group.h"

namespace talus {

const std::vector<std::string>& materialModelNames() {
  static const std::vector<std::string> names{"elastic"};
  return names;
}

namespace {

HenckyElasticity readElasticity(const ConfigTable& t) {
  const double E = t.positive("youngs_modulus");
  const double nu = t.inRange("poisson_ratio", 0.3, -1.0, 0.5, true, true);
  return HenckyElasticity::fromYoung(E, nu);
}

} // namespace

std::unique_ptr<MaterialGroup> createMaterialGroup(const ConfigTable& t, int index) {
  const std::string name = t.string("name");
  const std::string model = t.choice("model", "", materialModelNames());
  const double density = t.positive("density");
  if (model == "elastic") {
    ElasticModel m;
    m.elastic = readElasticity(t);
    return std::make_unique<SolidGroup<ElasticModel>>(name, index, density, m);
  }
  t.fail("model", "unsupported model '" + model + "'");
}

} // namespace talus
