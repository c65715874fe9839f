// JSON text written by hand (summary.json, the report pages): a string as a JSON literal.
#pragma once

#include <string>

namespace talus {

/// `s` as a JSON string literal, quotes included, with quotes, backslashes and control
/// characters escaped.
std::string jsonString(const std::string& s);

} // namespace talus
