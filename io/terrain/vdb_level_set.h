// A solid from an OpenVDB narrow-band level set (a .vdb file): terrain written by `talus terrain`,
// or a structure modelled elsewhere.
#pragma once

#include "engine/sdf.h"

#include <memory>
#include <string>

namespace talus {

/// How a level set's values come into memory.
enum class VdbLoading {
  /// All at once, every value checked: for files from elsewhere (`[terrain] sdf = ...`).
  Whole,
  /// The tree's layout at once, each leaf's values when first read (OpenVDB's delayed loading
  /// from the memory-mapped file), so a process holds only the terrain near what it samples;
  /// focus() then keeps the layout too only around the blocks a process works on (a rank: its
  /// part), read again from the file as they move. For files Talus wrote itself and renames
  /// into place whole (the terrain cache); their values are not checked up front, a non-finite
  /// one stops the block that reads it (sampleBlock throws).
  OnDemand,
};

class VdbLevelSet final : public Sdf {
public:
  /// Reads the float grid `gridName` (or the first float grid when empty) from `path`.
  /// `origin` is the world position of the simulation's local frame. Throws std::runtime_error
  /// for a file OpenVDB cannot read and for a grid that is not a usable level set (a fog volume,
  /// a non-uniform transform, a background <= 0, no active voxels, and with VdbLoading::Whole
  /// also non-finite values or nothing inside).
  VdbLevelSet(const std::string& path, const std::string& gridName, const Vec3d& origin,
              VdbLoading loading = VdbLoading::Whole);
  ~VdbLevelSet() override;

  bool sampleBlock(const BlockCoord& c, double dx, SdfBlock& out) const override;
  double distance(const Vec3d& x) const override;
  void bounds(Vec3d& lo, Vec3d& hi) const override; ///< active voxels, local frame
  std::string describe() const override;
  /// Bytes of the level set in memory now: the leaves whose values are loaded, and the tree's
  /// layout (about 100 bytes per leaf). With VdbLoading::OnDemand it grows as leaves are read.
  size_t residentBytes() const override;
  /// VdbLoading::OnDemand: keeps the tree within kFocusMargin blocks of [lo, hi] (re-read
  /// clipped from the file when the blocks leave what it holds, or hold less than a quarter of
  /// its plan area). Whole: no-op. distance() and sampleBlock() outside what is held throw
  /// std::logic_error instead of answering "outside".
  void focus(const BlockCoord& lo, const BlockCoord& hi, double dx) const override;
  static constexpr int kFocusMargin = 4;

  double voxelSize() const;
  /// World-space bounds of the level set's active voxels.
  void worldBounds(Vec3d& lo, Vec3d& hi) const;
  /// A metadata string of the grid ("" when absent), e.g. "crs_wkt".
  std::string metadata(const std::string& key) const;

private:
  void readWhole(const std::string& gridName);
  void check(bool values) const;
  void requireHeld(const Vec3d& lo, const Vec3d& hi) const;
  struct Impl;
  std::unique_ptr<Impl> impl_;
  Vec3d origin_;
  std::string path_;
  VdbLoading loading_;
  Vec3d boundsLo_, boundsHi_; ///< the whole file's active voxels, world frame
};

} // namespace talus
