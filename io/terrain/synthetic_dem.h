// Synthetic alpine terrain the project generates itself (no external data needed): a few named
// shapes with parameters, georeferenced in a real projected CRS (Swiss LV95 by default, so
// coordinates are ~2.6e6 m and the local-origin handling is exercised).
#pragma once

#include "io/config/config_table.h"
#include "io/common/raster_grid.h"

#include <string>
#include <vector>

namespace talus {

struct SyntheticDemKind {
  std::string name;
  std::string description;
  /// Shape parameters (name, default, meaning with unit).
  struct Param {
    std::string name;
    double value;
    std::string meaning;
  };
  std::vector<Param> params;
};

/// The kinds: slope_valley, vajont, cengalo, fluela, whymper.
const std::vector<SyntheticDemKind>& syntheticDemKinds();

/// Reads `kind` and its parameters from `spec` (unknown keys are left for checkAllUsed to
/// report) and returns the DEM. Common keys: cell_size (m, 5), origin = [x, y] world position of
/// the south-west corner ([2600000, 1200000]), crs ("EPSG:2056"), base_elevation (m), and
/// size = [x, y] extent (m, per kind). Throws InputError naming the key.
DemRaster makeSyntheticDem(const ConfigTable& spec);

/// A short text listing the kinds and their parameters (for `talus synth-dem --list`).
std::string syntheticDemHelp();

} // namespace talus
