// Names users give (materials, sections, structures) inside file, column and grid names:
// letters, digits, '_', '-' and '.' are kept, anything else becomes '_'.
#pragma once

#include <cctype>
#include <string>

namespace talus {

inline bool isSafeNameChar(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == '.';
}

inline std::string safeName(const std::string& s) {
  std::string out;
  for (char c : s) out += isSafeNameChar(c) ? c : '_';
  return out;
}

} // namespace talus
