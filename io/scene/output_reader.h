// The [output] section of a scene -> OutputSettings (docs/outputs.md lists every key).
#pragma once

#include "io/config/config_table.h"
#include "io/output/output_settings.h"

#include <string>
#include <vector>

namespace talus {

/// Reads an [output] table (nullptr = all defaults). Material names are checked against
/// `materialNames`. Throws InputError naming file, line and key.
OutputSettings readOutputSettings(const ConfigTable* output, const std::vector<std::string>& materialNames);

} // namespace talus
