// The fuzz target's contract, checked on its seed inputs in the normal suite: every input ends
// in a scene or an InputError, never another exception.
#include "io/common/input_error.h"
#include "io/scene/scene.h"

#include <filesystem>
#include <fstream>
#include <gtest/gtest.h>
#include <sstream>

using namespace talus;

TEST(FuzzSeeds, SeedScenesLoadAndTheirMutilationsFailCleanly) {
  const auto dir = std::filesystem::path(TALUS_SOURCE_DIR) / "tests" / "fuzz" / "seeds" / "scene";
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(dir)) {
    std::ifstream in(entry.path());
    std::stringstream ss;
    ss << in.rdbuf();
    const std::string text = ss.str();
    EXPECT_NO_THROW(loadSceneString(text, entry.path().filename().string())) << entry.path();
    // Every truncation of a seed must end in a clean InputError or a valid scene.
    for (size_t cut = 0; cut < text.size(); cut += 7) {
      try {
        loadSceneString(text.substr(0, cut), "cut.toml");
      } catch (const InputError&) {
      }
    }
    ++files;
  }
  EXPECT_GE(files, 2);
}
