#include "io/scene/material_presets.h"

namespace talus {

const std::map<std::string, MaterialPreset>& materialPresets() {
  static const std::map<std::string, MaterialPreset> presets{
      {"ice",
       {"drucker_prager", "Table 1, ice",
        {{"density", 917}, {"youngs_modulus", 9e6}, {"poisson_ratio", 0.25}, {"cohesion", 1e6},
         {"friction_angle", 40}, {"residual_friction_angle", 25}, {"softening", 1e10}}}},
      {"rock_vajont",
       {"drucker_prager", "Table 1, rock (Vajont: second cohesion, first friction angles)",
        {{"density", 2700}, {"youngs_modulus", 30e6}, {"poisson_ratio", 0.25}, {"cohesion", 2e6},
         {"friction_angle", 42}, {"residual_friction_angle", 36}, {"softening", 1e10}}}},
      {"rock_cengalo",
       {"drucker_prager", "Table 1, rock (Piz Cengalo: first cohesion, general friction angles)",
        {{"density", 2700}, {"youngs_modulus", 30e6}, {"poisson_ratio", 0.25}, {"cohesion", 1e7},
         {"friction_angle", 50}, {"residual_friction_angle", 30}, {"softening", 1e10}}}},
      {"rock",
       {"drucker_prager", "Table 1, rock (general values)",
        {{"density", 2700}, {"youngs_modulus", 30e6}, {"poisson_ratio", 0.25}, {"cohesion", 2e6},
         {"friction_angle", 50}, {"residual_friction_angle", 30}, {"softening", 1e10}}}},
      {"snow",
       {"cam_clay", "Table 1, snow",
        {{"density", 250}, {"youngs_modulus", 3e6}, {"poisson_ratio", 0.3}, {"critical_state_slope", 1.2},
         {"critical_state_slope_flowing", 0.4}, {"preconsolidation_pressure", 175e3}, {"tension_ratio", 0.4},
         {"hardening", 0.1}}}},
      {"water",
       {"water", "Table 1, water", {{"density", 1000}, {"bulk_modulus", 3e8}, {"tait_exponent", 7}}}},
  };
  return presets;
}

} // namespace talus
