// Write-then-rename, so a run killed mid-write never leaves a truncated output behind.
#pragma once

#include <filesystem>
#include <functional>
#include <string>

namespace talus {

/// Calls write(tmpPath), then renames tmpPath to path (atomic on POSIX file systems).
inline void writeAtomically(const std::string& path, const std::function<void(const std::string&)>& write) {
  const std::string tmp = path + ".tmp";
  try {
    write(tmp);
  } catch (...) {
    std::error_code ec;
    std::filesystem::remove(tmp, ec);
    throw;
  }
  std::filesystem::rename(tmp, path);
}

} // namespace talus
