// Solids as signed distance fields (negative inside): the terrain, structures. Sampled once per block.
//
// Sampling a level set costs hundreds of ns per query, so the engine never samples per particle:
// SdfCache evaluates phi and the outward normal at the 512 nodes of a block the first time
// the block becomes active and keeps them for the rest of the run (terrain is static).
#pragma once

#include "engine/types.h"

#include <memory>
#include <string>
#include <unordered_map>
#include <vector>

namespace talus {

class BlockTopology;

/// A signed distance and its outward normals at the nodes of one block.
struct SdfBlock {
  float phi[kBlockNodes];
  float normal[kBlockNodes][3];
};

class Sdf {
public:
  virtual ~Sdf() = default;
  /// phi and unit outward normal at nodes (8c + l) * dx of the local frame, blockNodeIndex order.
  /// Returns false when no node of the block is inside the solid (nothing to constrain). By
  /// default node by node through distance() and normal(x, dx/4); level sets sample faster.
  virtual bool sampleBlock(const BlockCoord& c, double dx, SdfBlock& out) const;
  /// Signed distance at one point of the local frame (setup, tests and moving colliders; never
  /// per particle).
  virtual double distance(const Vec3d& x) const = 0;
  /// Unit outward normal at x: central differences of distance() at +-h (zero where they vanish).
  virtual Vec3d normal(const Vec3d& x, double h) const;
  /// Box holding the solid's surface (local frame); unbounded when unknown.
  virtual void bounds(Vec3d& lo, Vec3d& hi) const;
  virtual std::string describe() const = 0;
  /// Bytes this solid holds in memory (a level set's loaded values); 0 for analytic solids.
  virtual size_t residentBytes() const { return 0; }
  /// From now on, distance(), normal() and sampleBlock() are asked only within the blocks
  /// [lo, hi] (inclusive, at dx) and one block around them, until the next call. A solid read
  /// from a file may then drop what lies farther (a rank's terrain shrinks to its part) and
  /// read again what a later call asks for; its values do not change. Not thread-safe: call
  /// between parallel phases. A query outside may throw std::logic_error. Default: no-op.
  virtual void focus(const BlockCoord& lo, const BlockCoord& hi, double dx) const { (void)lo, (void)hi, (void)dx; }
};

/// The plane through `point` with upward unit normal `normal` (local frame).
class PlaneSdf final : public Sdf {
public:
  PlaneSdf(const Vec3d& point, const Vec3d& normal);
  double distance(const Vec3d& x) const override { return normal_.dot(x - point_); }
  Vec3d normal(const Vec3d&, double) const override { return normal_; }
  std::string describe() const override;

private:
  Vec3d point_, normal_;
};

class SdfCache {
public:
  /// @param focus  tell the solid which blocks are active at each attach (Sdf::focus); false
  ///               when something else queries the solid elsewhere during the run
  SdfCache(std::shared_ptr<const Sdf> sdf, double dx, bool focus = true) : sdf_(std::move(sdf)), dx_(dx), focus_(focus) {}
  /// Fill `out[b]` for every active block: its cached data, or nullptr when it holds no ground node.
  void attach(const BlockTopology& topo, std::vector<const SdfBlock*>& out);
  size_t memoryBytes() const { return blocks_.size() * sizeof(SdfBlock) + slots_.size() * 16; }

private:
  std::shared_ptr<const Sdf> sdf_;
  double dx_;
  bool focus_;
  std::unordered_map<uint64_t, int32_t> slots_; ///< block key -> index in blocks_, -1 when empty
  std::vector<std::unique_ptr<SdfBlock>> blocks_;
};

} // namespace talus
