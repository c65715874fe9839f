// Terrain as a signed distance field (negative inside the ground), sampled once per block.
//
// Sampling a level set costs hundreds of ns per query, so the engine never samples per particle:
// TerrainCache evaluates phi and the outward normal at the 512 nodes of a block the first time
// the block becomes active and keeps them for the rest of the run (terrain is static).
#pragma once

#include "engine/boundary.h"
#include "engine/types.h"

#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

namespace talus {

class BlockTopology;

/// Cached ground SDF at the nodes of one block.
struct TerrainBlock {
  float phi[kBlockNodes];
  float normal[kBlockNodes][3];
};

class TerrainSdf {
public:
  virtual ~TerrainSdf() = default;
  /// phi and unit outward normal at nodes (8c + l) * dx of the local frame, blockNodeIndex order.
  /// Returns false when no node of the block is inside the ground (nothing to constrain).
  virtual bool sampleBlock(const BlockCoord& c, double dx, TerrainBlock& out) const = 0;
  /// Signed distance at one point of the local frame (setup and tests only, not per step).
  virtual double distance(const Vec3d& x) const = 0;
  virtual std::string describe() const = 0;
};

/// The plane through `point` with upward unit normal `normal` (local frame).
class PlaneTerrain final : public TerrainSdf {
public:
  PlaneTerrain(const Vec3d& point, const Vec3d& normal);
  bool sampleBlock(const BlockCoord& c, double dx, TerrainBlock& out) const override;
  double distance(const Vec3d& x) const override { return normal_.dot(x - point_); }
  std::string describe() const override;

private:
  Vec3d point_, normal_;
};

class TerrainCache {
public:
  TerrainCache(std::shared_ptr<const TerrainSdf> sdf, double dx) : sdf_(std::move(sdf)), dx_(dx) {}
  /// Fill `out[b]` for every active block: its cached data, or nullptr when it holds no ground node.
  void attach(const BlockTopology& topo, std::vector<const TerrainBlock*>& out);
  size_t cachedBlocks() const { return blocks_.size(); }
  size_t memoryBytes() const { return blocks_.size() * sizeof(TerrainBlock) + slots_.size() * 16; }
  const TerrainSdf& sdf() const { return *sdf_; }

private:
  std::shared_ptr<const TerrainSdf> sdf_;
  double dx_;
  std::unordered_map<uint64_t, int32_t> slots_; ///< block key -> index in blocks_, -1 when empty
  std::vector<std::unique_ptr<TerrainBlock>> blocks_;
};

} // namespace talus
