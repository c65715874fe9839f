// A solid from an OpenVDB narrow-band level set (a .vdb file): terrain written by `talus terrain`,
// or a structure modelled elsewhere.
#pragma once

#include "engine/sdf.h"

#include <memory>
#include <string>

namespace talus {

class VdbLevelSet final : public Sdf {
public:
  /// Reads the float grid `gridName` (or the first float grid when empty) from `path`.
  /// `origin` is the world position of the simulation's local frame. Throws std::runtime_error
  /// for a file OpenVDB cannot read and for a grid that is not a usable level set (a fog volume,
  /// a non-uniform transform, a background <= 0, no active voxels, non-finite values, nothing
  /// inside).
  VdbLevelSet(const std::string& path, const std::string& gridName, const Vec3d& origin);
  ~VdbLevelSet() override;

  bool sampleBlock(const BlockCoord& c, double dx, SdfBlock& out) const override;
  double distance(const Vec3d& x) const override;
  void bounds(Vec3d& lo, Vec3d& hi) const override; ///< active voxels, local frame
  std::string describe() const override;

  double voxelSize() const;
  /// World-space bounds of the level set's active voxels.
  void worldBounds(Vec3d& lo, Vec3d& hi) const;
  /// A metadata string of the grid ("" when absent), e.g. "crs_wkt".
  std::string metadata(const std::string& key) const;

private:
  void check() const;
  struct Impl;
  std::unique_ptr<Impl> impl_;
  Vec3d origin_;
  std::string path_;
};

} // namespace talus
