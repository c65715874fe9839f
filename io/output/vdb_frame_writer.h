// OpenVDB frames: frames/volume_NNNNN.vdb (fog volumes for renderers: Blender, Houdini, ...)
// and optionally frames/points_NNNNN.vdb (OpenVDB points, for Houdini; Blender rejects them).
// Both live in one translation unit: OpenVDB headers cost most of a minute to compile.
#pragma once

#include "io/output/output_observer.h"

#include <string>
#include <utility>
#include <vector>

namespace talus {

/// Float grids `density` (kg/m3) and `fraction_<material>` (volume fraction, material volume at
/// its reference density per voxel volume) and Vec3f `velocity` (m/s, mass-weighted), one voxel
/// per grid node (dx), placed at world coordinates; Blosc compressed; file and grid metadata
/// `time` (s) and `units`. `crsWkt` (may be empty) is stored as file metadata `crs_wkt`.
void writeVolumeVdb(const std::string& path, const Simulation& sim, const std::string& crsWkt = "");

/// One PointDataGrid `points`: positions (world), attributes `v` (Vec3f, m/s), `mass` (float,
/// kg) and `material` (int32, scene material index). Voxel size dx.
void writePointsVdb(const std::string& path, const Simulation& sim, const std::string& crsWkt = "");

/// What a volume frame (writeVolumeVdb's file) holds, read without its voxel data but for the
/// density grid's active bounds.
struct VolumeFrameInfo {
  Vec3d localOrigin = Vec3d::Zero();      ///< file metadata `local_origin`
  bool empty = true;                      ///< no active density voxel
  Vec3d lo = Vec3d::Zero(), hi = Vec3d::Zero(); ///< world bounds of the active density voxels
  double time = 0;
  /// Per fraction grid: the grid's name suffix (after `fraction_`) and reference density (kg/m3).
  std::vector<std::pair<std::string, double>> materials;
};
/// Throws InputError naming the file when it cannot be read or is not a Talus volume frame.
VolumeFrameInfo readVolumeFrameInfo(const std::string& path);

class VdbVolumeWriter final : public OutputObserver {
public:
  VdbVolumeWriter(std::string outDir, std::string crsWkt);
  std::string name() const override { return "vdb_frames"; }
  void onFrame(const Simulation& sim, int index) override;
  bool framesInParts() const override { return true; }
  std::optional<WriteError> onFrameParts(Communicator& comm, const Simulation& local, int index) override;

private:
  std::string outDir_, crsWkt_;
};

class VdbPointsWriter final : public OutputObserver {
public:
  VdbPointsWriter(std::string outDir, std::string crsWkt);
  std::string name() const override { return "vdb_points"; }
  void onFrame(const Simulation& sim, int index) override;

private:
  std::string outDir_, crsWkt_;
};

} // namespace talus
