// The two slabs of the hazard-map tests: a snow slab 0.4 m thick sliding at 2 m/s (no gravity, so
// it translates rigidly) beside a rock slab at rest, at national grid coordinates (the map tests
// add a DEM of 0.2 m cells rising 0.5 m per m eastwards).
#pragma once

#include "io/output/hazard_maps.h"

#include <functional>

namespace talus::test {

/// Per-material maps over `sim`'s domain on 0.15 m cells (no DEM), made in `dir`.
inline std::unique_ptr<HazardMaps> slabMaps(const Simulation& sim, const std::string& dir,
                                            const std::function<void(MapSettings&)>& edit = {}) {
  MapSettings ms;
  ms.enabled = true;
  ms.perMaterial = true;
  if (edit) edit(ms);
  RunContext run;
  run.origin = sim.settings().origin;
  run.domainMin = sim.settings().domain.min, run.domainMax = sim.settings().domain.max;
  return std::make_unique<HazardMaps>(dir, HazardMaps::domainGrid(run, 0.15), nullptr, ms);
}

inline const char* kSlabs = R"([simulation]
dx = 0.1
end_time = 0.5
gravity = [0, 0, 0]
[domain]
min = [2600000, 1200000, 1000]
max = [2600004, 1200003, 1002]
[[materials]]
name = "snow"
model = "elastic"
density = 300
youngs_modulus = 1e4
[[materials]]
name = "rock"
model = "elastic"
density = 2500
youngs_modulus = 1e5
[[bodies]]
material = "snow"
shape = "box"
min = [2600000.4, 1200000.4, 1000.2]
max = [2600002.4, 1200001.2, 1000.6]
velocity = [2, 0, 0]
[[bodies]]
material = "rock"
shape = "box"
min = [2600003.0, 1200001.8, 1000.2]
max = [2600003.6, 1200002.6, 1000.6]
[output.maps]
per_material = true
erodible = ["snow"]
)";

} // namespace talus::test
