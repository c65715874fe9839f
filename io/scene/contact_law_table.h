// Contact laws by name: the table scenes choose from (`walls`, `[terrain] boundary`, a face's or
// a structure's `law`). Each row reads its parameters; adding a law is its type in engine/ and
// one row here.
#pragma once

#include "engine/contact_law.h"
#include "io/config/config_table.h"

#include <memory>
#include <string>
#include <vector>

namespace talus {

/// Names the table knows (for messages and docs), without "open".
std::vector<std::string> contactLawNames();

/// The law named by `t[key]` (or `fallback` when absent), its parameters read from `t` under
/// `prefix` + the parameter's name (e.g. "wall_friction" in [domain]). `key` may also hold an
/// inline table { law = "...", parameters... }, whose keys are read without the prefix.
/// "open" returns null when `allowOpen`, else it is an error. Throws InputError.
std::shared_ptr<const ContactLaw> readContactLaw(const ConfigTable& t, const std::string& key,
                                                 const std::string& fallback, const std::string& prefix,
                                                 bool allowOpen);

} // namespace talus
