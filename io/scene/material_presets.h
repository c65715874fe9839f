// Table 1 of the paper as named presets (`preset = "rock"` in a [[materials]] table).
#pragma once

#include <map>
#include <string>
#include <vector>

namespace talus {

struct MaterialPreset {
  std::string model;
  std::string source;                  ///< where the numbers come from
  std::map<std::string, double> values; ///< scene keys and their values (scene units)
};

/// ice, rock_vajont, rock_cengalo, rock, snow, water. Elastic moduli of rock and ice are the
/// paper's already-reduced values (Table 1 footnote); `elastic_scale` changes them further.
const std::map<std::string, MaterialPreset>& materialPresets();

} // namespace talus
