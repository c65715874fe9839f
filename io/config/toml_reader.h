// TOML scene text -> ConfigTable (with source lines), and `--set key=value` overrides.
#pragma once

#include "io/config/config_table.h"

#include <memory>
#include <string>

namespace talus {

/// `text`, when given, receives the file's bytes (the scene hash is taken over them).
std::shared_ptr<ConfigTable> readTomlFile(const std::string& path, std::string* text = nullptr);
std::shared_ptr<ConfigTable> readTomlString(const std::string& text, const std::string& name);

/// Applies "section.key=value" (value in TOML syntax; a bare word is taken as a string).
/// Arrays of tables are addressed by index or by name: materials.rock.density=2500.
void applyOverride(ConfigTable& root, const std::string& assignment);

} // namespace talus
