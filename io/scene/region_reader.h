// [[terrain.regions]]: the terrain law's parameters by region, over the law's own values, applied
// in order (a later region wins where they overlap), as AvaFrame's spatial Voellmy does:
//   { polygon = "forest.shp", friction = 0.3, xi = 1500 }   inside the polygons
//   { raster = "xi.tif", parameter = "xi" }                 a raster GDAL reads, bilinear
//   { polygon = "forest.shp", resistance = 0.01 }           a forest's drag (any law)
#pragma once

#include "engine/contact_law.h"
#include "engine/parameter_field.h"
#include "engine/simulation.h"
#include "io/config/config_table.h"

#include <memory>
#include <string>

namespace talus {

/// The field of the terrain law's parameters, or null when the scene gives no regions. `demCrs`
/// is the terrain's CRS (WKT, "" when unknown). Throws InputError naming the file or key: a
/// region file in another CRS, a raster that does not overlap the domain or has no-data or
/// negative values inside it, a parameter the law does not have.
std::shared_ptr<const ParameterField> readTerrainRegions(const ConfigTable& terrain, const ContactLaw& law,
                                                         const SimulationSettings& settings, const std::string& demCrs);

/// settings.terrainLaw ([terrain] boundary, default Coulomb `friction`) and
/// settings.terrainParameters (its regions). A region that sets `resistance` (a forest's drag,
/// cResH in 1/m) wraps the law in engine/resistance_law.h's ResistedLaw; without one the law is
/// as read. Throws InputError as readContactLaw and readTerrainRegions.
void readTerrainLaw(const ConfigTable& terrain, SimulationSettings& settings, const std::string& demCrs);

} // namespace talus
