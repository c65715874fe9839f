// Behaviour guard: the shipped scenes' first 100 steps give the particle state recorded in
// tests/data/scene_checksums.txt (a hash of every particle array and model scalar). Recorded with
// the portable float Release build of g++ before the colliders/io restructuring (issue 12); a
// change that moves any bit of any particle fails here. Other builds (double, sanitizers, clang)
// round differently and skip. To re-record after an intended change of the numerics:
//   TALUS_RECORD_CHECKSUMS=1 build/tests/talus_tests --gtest_filter='SceneChecksums.*'
#include "io/scene/scene.h"
#include "terrain_test_support.h"

#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <gtest/gtest.h>
#include <map>
#include <sstream>

using namespace talus;

namespace {

constexpr int kSteps = 100;

std::string checksumFile() { return std::string(TALUS_SOURCE_DIR) + "/tests/data/scene_checksums.txt"; }

/// The build the checksums were recorded with: the same compiler, precision and flags round alike.
std::string buildTag() {
#if defined(__clang__)
  std::string c = "clang";
#elif defined(__GNUC__)
  std::string c = "gcc" + std::to_string(__GNUC__);
#else
  std::string c = "other";
#endif
#if defined(__SANITIZE_ADDRESS__) || defined(TALUS_SANITIZED)
  c += "-asan";
#endif
#if defined(__has_feature)
#if __has_feature(address_sanitizer)
  c += "-asan";
#endif
#endif
#if defined(__AVX__) || defined(__FMA__)
  c += "-native";
#endif
  return c + "-real" + std::to_string(sizeof(Real) * 8);
}

struct Fnv {
  uint64_t h = 1469598103934665603ull;
  void add(const void* data, size_t n) {
    const auto* b = static_cast<const unsigned char*>(data);
    for (size_t i = 0; i < n; ++i) h = (h ^ b[i]) * 1099511628211ull;
  }
  template <class T> void addVector(const std::vector<T>& v) { add(v.data(), v.size() * sizeof(T)); }
};

/// Hash of every particle array (x, v, C, tau, mass) and every model scalar (pressure, plastic
/// strains, J), group by group. Model scalars are hashed instead of raw state structs, whose
/// padding bytes are not defined.
std::string stateHash(const Simulation& sim) {
  Fnv f;
  for (const MaterialGroup* g : sim.groups()) {
    f.add(g->name().data(), g->name().size());
    const ParticleSet& P = g->particles;
    f.addVector(P.x), f.addVector(P.v), f.addVector(P.C), f.addVector(P.tau), f.addVector(P.mass);
    std::vector<float> s;
    for (const auto& name : g->scalarNames()) {
      g->scalar(name, s);
      f.addVector(s);
    }
  }
  char buf[32];
  std::snprintf(buf, sizeof buf, "%016llx", static_cast<unsigned long long>(f.h));
  return buf;
}

std::map<std::string, std::string> readRecorded() {
  std::map<std::string, std::string> m;
  std::ifstream in(checksumFile());
  std::string line;
  while (std::getline(in, line)) {
    if (line.empty() || line[0] == '#') continue;
    std::istringstream s(line);
    std::string key, hash;
    s >> key >> hash;
    m[key] = hash;
  }
  return m;
}

void checkScene(const std::string& name) {
  const bool record = std::getenv("TALUS_RECORD_CHECKSUMS") != nullptr;
  const auto recorded = readRecorded();
  const std::string key = buildTag() + "/" + name;
  // Other builds round differently: skip before spending minutes (under sanitizers) on the run.
  if (!record && !recorded.count(key))
    GTEST_SKIP() << "no checksum recorded for build " << buildTag() << " (see the file's header)";
  test::useTestTerrainCache();
  const std::string file = std::string(TALUS_SOURCE_DIR) + "/data/scenes/" + name + ".toml";
  SceneSetup s = loadSceneFile(file);
  Simulation sim(s.settings, std::move(s.groups));
  for (int i = 0; i < kSteps; ++i) sim.step();
  const std::string hash = stateHash(sim);
  std::printf("%s %s (%zu particles, t = %.6g s)\n", key.c_str(), hash.c_str(), sim.particleCount(), sim.time());
  if (record) {
    std::ofstream(checksumFile(), std::ios::app) << key << " " << hash << "\n";
    return;
  }
  EXPECT_EQ(hash, recorded.at(key)) << name << ": the first " << kSteps << " steps no longer give the recorded particle state";
}

} // namespace

TEST(SceneChecksums, DefaultScene) { checkScene("default"); }
TEST(SceneChecksums, SlopeValley) { checkScene("slope_valley"); }
TEST(SceneChecksums, Vajont) { checkScene("vajont"); }
TEST(SceneChecksums, Cengalo) { checkScene("cengalo"); }
TEST(SceneChecksums, Fluela) { checkScene("fluela"); }
TEST(SceneChecksums, Whymper) { checkScene("whymper"); }
TEST(SceneChecksums, Wolfsgruben) {
  if (test::sharedDir().empty()) GTEST_SKIP() << "../shared (AvaFrame avaWog data) not found";
  checkScene("wolfsgruben");
}
