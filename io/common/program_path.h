// Finding an optional external program (ffmpeg, blender) on the PATH.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <string>
#include <unistd.h>

namespace talus {

/// The executable `name` on the PATH, or "" when there is none.
inline std::string findProgram(const std::string& name) {
  const char* path = std::getenv("PATH");
  const std::string p = path ? path : "";
  for (size_t a = 0; a <= p.size();) {
    const size_t b = std::min(p.find(':', a), p.size());
    const std::filesystem::path exe = std::filesystem::path(p.substr(a, b - a)) / name;
    if (b > a && access(exe.c_str(), X_OK) == 0) return exe.string();
    a = b + 1;
  }
  return "";
}

} // namespace talus
