// Terrain from an OpenVDB narrow-band level set (a .vdb file, e.g. written by `talus terrain`).
#pragma once

#include "engine/terrain.h"

#include <memory>
#include <string>

namespace talus {

class LevelSetTerrain final : public TerrainSdf {
public:
  /// Reads the float grid `gridName` (or the first float grid when empty) from `path`.
  /// `origin` is the world position of the simulation's local frame. Throws std::runtime_error.
  LevelSetTerrain(const std::string& path, const std::string& gridName, const Vec3d& origin);
  ~LevelSetTerrain() override;

  bool sampleBlock(const BlockCoord& c, double dx, TerrainBlock& out) const override;
  double distance(const Vec3d& x) const override;
  std::string describe() const override;

  double voxelSize() const;
  /// World-space bounds of the level set's active voxels.
  void worldBounds(Vec3d& lo, Vec3d& hi) const;
  /// A metadata string of the grid ("" when absent), e.g. "crs_wkt".
  std::string metadata(const std::string& key) const;

private:
  struct Impl;
  std::unique_ptr<Impl> impl_;
  Vec3d origin_;
  std::string path_;
};

} // namespace talus
