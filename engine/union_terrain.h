// Terrain made of several parts: the union of their solids (phi = min over the parts). Fixed
// regions of a scene (static boundary geometry) are added to the DEM's level set this way.
#pragma once

#include "engine/terrain.h"

#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace talus {

class UnionTerrain final : public TerrainSdf {
public:
  explicit UnionTerrain(std::vector<std::shared_ptr<const TerrainSdf>> parts) : parts_(std::move(parts)) {}
  /// Per node the part with the smallest phi wins (its phi and normal). Parts reporting no
  /// ground in a block are skipped: their phi there is positive, which never decides a contact.
  bool sampleBlock(const BlockCoord& c, double dx, TerrainBlock& out) const override;
  double distance(const Vec3d& x) const override;
  std::string describe() const override;

private:
  std::vector<std::shared_ptr<const TerrainSdf>> parts_;
};

/// A solid given by an analytic signed distance function of the local frame (negative inside).
/// Normals are central differences of the function at +-dx/4.
class FunctionTerrain final : public TerrainSdf {
public:
  FunctionTerrain(std::function<double(const Vec3d&)> sdf, std::string description)
      : sdf_(std::move(sdf)), description_(std::move(description)) {}
  bool sampleBlock(const BlockCoord& c, double dx, TerrainBlock& out) const override;
  double distance(const Vec3d& x) const override { return sdf_(x); }
  std::string describe() const override { return description_; }

private:
  std::function<double(const Vec3d&)> sdf_;
  std::string description_;
};

} // namespace talus
