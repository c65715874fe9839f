// frames/particles_NNNNN.ply: particles as a binary PLY point cloud, which Blender (File >
// Import > Stanford PLY) and ParaView read directly; Blender does not import VDB points.
#pragma once

#include "io/output/output_observer.h"

#include <array>

namespace talus {

/// Writes every particle as a PLY vertex: x, y, z (double, world coordinates, m), vx, vy, vz
/// (float, m/s), mass (float, kg), material (int, index into the scene's materials) and red,
/// green, blue (uchar, a colour per material so viewers show materials apart).
/// Throws WriteError naming `path`.
void writeParticlesPly(const std::string& path, const Simulation& sim);
/// The same file written by every process with its own particles, collectively (as
/// writeParticlesH5's parts). Returns on rank 0 the first failure (nothing elsewhere).
std::optional<WriteError> writeParticlesPly(Communicator& comm, const std::string& path, const Simulation& local);

/// Display colour of material `index` (shared by the PLY writer and the plots).
std::array<unsigned char, 3> materialColour(int index);

class PlyFrameWriter final : public OutputObserver {
public:
  explicit PlyFrameWriter(std::string outDir);
  std::string name() const override { return "ply_frames"; }
  void onFrame(const Simulation& sim, int index) override;
  bool framesInParts() const override { return true; }
  std::optional<WriteError> onFrameParts(Communicator& comm, const Simulation& local, int index) override;

private:
  std::string outDir_;
};

} // namespace talus
