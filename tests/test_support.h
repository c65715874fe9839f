// Helpers shared by the test files: build a Simulation from scene text, measure particles.
#pragma once

#include "engine/simulation.h"
#include "io/scene/scene.h"

#include <array>
#include <cstdio>
#include <filesystem>
#include <sys/wait.h>
#include <memory>
#include <string>

namespace talus::test {

inline std::unique_ptr<Simulation> makeSimulation(const std::string& toml,
                                                  const std::vector<std::string>& overrides = {}) {
  SceneSetup s = loadSceneString(toml, "test.toml", overrides);
  return std::make_unique<Simulation>(s.settings, std::move(s.groups));
}

inline Vec3d centreOfMass(const Simulation& sim) { return sim.centreOfMass(); }
inline Vec3d meanVelocity(const Simulation& sim) { return sim.meanVelocity(); }

/// Every group's positions and velocities as bytes: equal bytes, bit-identical particles.
inline std::vector<char> particleBytes(const Simulation& sim) {
  std::vector<char> bytes;
  for (const auto* g : sim.groups())
    for (const auto& v : {g->particles.x, g->particles.v}) {
      const char* p = reinterpret_cast<const char*>(v.data());
      bytes.insert(bytes.end(), p, p + v.size() * sizeof(v[0]));
    }
  return bytes;
}

/// ../shared next to the project, or empty when absent (tests then skip).
inline std::string sharedDir() {
  const std::string d = TALUS_SHARED_DIR;
  return std::filesystem::is_directory(d) ? d : std::string();
}

/// Runs the talus binary with `args`; returns its exit status and fills `out` with its stdout and
/// stderr.
inline int runTalus(const std::string& args, std::string& out) {
  const std::string cmd = "\"" TALUS_BINARY "\" " + args + " 2>&1";
  FILE* pipe = popen(cmd.c_str(), "r");
  if (!pipe) return -1;
  std::array<char, 4096> buf{};
  out.clear();
  while (fgets(buf.data(), int(buf.size()), pipe)) out += buf.data();
  const int status = pclose(pipe);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -1;
}

inline std::string tempDir(const std::string& name) {
  auto p = std::filesystem::temp_directory_path() / ("talus_test_" + name);
  std::filesystem::remove_all(p);
  std::filesystem::create_directories(p);
  return p.string();
}

} // namespace talus::test
