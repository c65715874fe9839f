// Builds a material group from a [[materials]] table of the scene.
#pragma once

#include "io/config/config_table.h"
#include "engine/material_group.h"

#include <memory>

namespace talus {

/// Reads `model`, `preset` and the model's keys; throws InputError on bad or missing values.
std::unique_ptr<MaterialGroup> createMaterialGroup(const ConfigTable& table, int index);

/// Names of the models `model = "..."` accepts.
const std::vector<std::string>& materialModelNames();

} // namespace talus
