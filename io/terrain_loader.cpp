#include "io/terrain_loader.h"

#include "engine/level_set_terrain.h"

#include <filesystem>

namespace talus {

std::string resolveScenePath(const std::string& sceneFile, const std::string& path) {
  namespace fs = std::filesystem;
  if (path.empty() || fs::path(path).is_absolute()) return path;
  const fs::path dir = fs::path(sceneFile).parent_path();
  return (dir / path).lexically_normal().string();
}

std::shared_ptr<const TerrainSdf> loadTerrain(const ConfigTable& t, const SimulationSettings& s) {
  const bool hasPlane = t.has("plane"), hasSdf = t.has("sdf");
  if (hasPlane + hasSdf != 1) t.fail("", "give exactly one of 'plane' or 'sdf'");
  if (hasPlane) {
    const ConfigTable* p = t.table("plane");
    const Vec3d n = p->vec3("normal");
    if (!(n.norm() > 0)) p->fail("normal", "must be a non-zero vector");
    return std::make_shared<PlaneTerrain>(p->vec3("point") - s.origin, n);
  }
  const std::string file = resolveScenePath(t.file(), t.string("sdf"));
  if (!std::filesystem::exists(file)) t.fail("sdf", "file not found: " + file);
  try {
    return std::make_shared<LevelSetTerrain>(file, t.string("grid", ""), s.origin);
  } catch (const std::exception& e) {
    t.fail("sdf", file + ": " + e.what());
  }
}

} // namespace talus
