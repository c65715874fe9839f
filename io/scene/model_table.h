// The table of material models: each row is a `model = "..."` name, the reader of its keys and the
// constructor of its material group. Adding a model is its type in materials/ and one row here.
#pragma once

#include "engine/material_group.h"
#include "io/config/config_table.h"

#include <memory>
#include <string>
#include <vector>

namespace talus {

/// Reads `model` (or a `preset`) and that model's keys from a [[materials]] table and builds the
/// group; a model name not in the table is an error naming the valid ones. Throws InputError.
std::unique_ptr<MaterialGroup> createMaterialGroup(const ConfigTable& table, int index);

/// The model names, in table order.
std::vector<std::string> materialModelNames();

} // namespace talus
