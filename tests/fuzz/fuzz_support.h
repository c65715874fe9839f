// Shared by the libFuzzer targets: inputs become files (the readers take paths), and the rule
// every target checks: a reader ends in a value or in the one exception type its callers turn
// into a one-line message; anything else (a crash, a sanitizer report, another exception) is a
// bug, reported by abort().
#pragma once

#include "io/common/resource_limits.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

namespace talus::fuzz {

/// A folder of this process's own under the temp dir.
inline const std::string& workDir() {
  static const std::string d = [] {
    const auto p = std::filesystem::temp_directory_path() / ("talus_fuzz_" + std::to_string(::getpid()));
    std::filesystem::create_directories(p);
    return p.string();
  }();
  return d;
}

inline std::string writeInput(const std::string& name, const uint8_t* data, size_t size) {
  const std::string path = workDir() + "/" + name;
  std::ofstream(path, std::ios::binary | std::ios::trunc).write(reinterpret_cast<const char*>(data), std::streamsize(size));
  return path;
}

/// Small limits keep every input within the fuzzer's memory and time budget.
inline void smallLimits() {
  resourceLimits().maxParticles = 2e5;
  resourceLimits().maxRasterCells = 2e5;
  resourceLimits().maxVoxels = 2e6;
}

[[noreturn]] inline void fail(const char* target, const char* what) {
  std::fprintf(stderr, "%s: an unexpected exception escaped: %s\n", target, what);
  std::abort();
}

} // namespace talus::fuzz
