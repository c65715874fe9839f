// libFuzzer target for the scene reader: TOML text -> ConfigTable -> materials, terrain, bodies.
// Any input must end in a scene or in talus::InputError; anything else (a crash, a sanitizer
// report, another exception type escaping) is a bug.
#include "io/common/input_error.h"
#include "io/common/resource_limits.h"
#include "io/scene/scene.h"

#include <cstdint>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <string>

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  // Small limits keep every input within the fuzzer's memory and time budget.
  talus::resourceLimits().maxParticles = 2e5;
  talus::resourceLimits().maxRasterCells = 2e5;
  talus::resourceLimits().maxVoxels = 2e6;
  // Generated terrains are cached on disk; keep the fuzzer's away from the user's cache.
  const auto dir = std::filesystem::temp_directory_path() / "talus_fuzz_cache";
  std::filesystem::create_directories(dir);
  setenv("TALUS_CACHE_DIR", dir.c_str(), 1);
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size > 16384) return 0; // scene files are small; longer inputs only slow the search
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    talus::SceneSetup s = talus::loadSceneString(text, "fuzz.toml");
  } catch (const talus::InputError&) {
    // the expected outcome for bad input
  } catch (const std::exception& e) {
    std::fprintf(stderr, "scene reader let a non-InputError escape: %s\n", e.what());
    std::abort();
  }
  return 0;
}
