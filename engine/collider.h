// Colliders: everything the material can push against. A collider is a geometry (a face of the
// domain box, or a signed distance: the terrain, a plane, a box, a cylinder, a level set), a
// contact law, and a motion (at rest, or a prescribed translation and rotation over a time
// window: a gate that opens, a moving wall). Each step a collider constrains the grid nodes
// inside it and records the load it takes: the momentum its contacts removed from the material.
#pragma once

#include "engine/block_topology.h"
#include "engine/contact_law.h"
#include "engine/parameter_field.h"
#include "engine/sdf.h"

#include <cmath>
#include <limits>
#include <memory>
#include <unordered_map>
#include <string>
#include <vector>

namespace talus {

/// Rigid motion of a collider from its rest pose: translation at `velocity` and rotation at
/// `angularVelocity` about `pivot` (local frame, rest pose), both during [start, stop).
struct ColliderMotion {
  Vec3d velocity = Vec3d::Zero();        ///< m/s
  Vec3d angularVelocity = Vec3d::Zero(); ///< rad/s
  Vec3d pivot = Vec3d::Zero();
  double start = 0, stop = std::numeric_limits<double>::infinity();

  bool moves() const { return (velocity.squaredNorm() > 0 || angularVelocity.squaredNorm() > 0) && stop > start; }
  /// Pose at time t: a rest point x0 is at R (x0 - pivot) + pivot + d.
  void pose(double t, Mat3d& R, Vec3d& d) const;
  /// Velocity of the collider's point now at x, at time t.
  Vec3d velocityAt(const Vec3d& x, double t) const;
};

/// The load a collider took in one step: force (N) and moment (N m) about its reference point,
/// both from the material onto the collider.
struct ColliderLoad {
  Vec3d force = Vec3d::Zero();
  Vec3d moment = Vec3d::Zero();
};

/// The contact nodes of one block for one collider (filled by Collider::gather).
struct ContactBatch {
  int count = 0;           ///< nodes the law acts on
  int held = 0;            ///< nodes deep inside with no usable normal: moved with the collider
  int16_t node[kBlockNodes];   ///< law nodes first, then held nodes from the end
  ContactNode contact[kBlockNodes];
  Vec3 velocity[kBlockNodes];  ///< the collider's velocity at each node (zero when at rest)
  // Scratch for laws mixed by material (engine/grid_update.cpp): the nodes as gathered, and the
  // mass-weighted sum of the laws' velocities.
  ContactNode original[kBlockNodes];
  Vec3 mixed[kBlockNodes];
};

class Collider {
public:
  /// A solid bounded by `sdf` (rest pose, local frame; negative inside). `reference` is the point
  /// moments are taken about (local frame, rest pose; it moves with the collider).
  Collider(std::string name, std::shared_ptr<const Sdf> sdf, std::shared_ptr<const ContactLaw> law,
           ColliderMotion motion, const Vec3d& reference);
  /// Face `axis` (0, 1, 2) of the domain box: nodes at or beyond local coordinate `at` (below it
  /// for the lower face, above it for the upper face) are in contact.
  static Collider face(std::string name, int axis, bool upper, double at, std::shared_ptr<const ContactLaw> law);
  /// The part of that face whose nodes' two other coordinates lie within [lo, hi] (local frame).
  static Collider panel(std::string name, int axis, bool upper, double at, std::shared_ptr<const ContactLaw> law,
                        const Vec3d& lo, const Vec3d& hi);
  /// The node row a face at coordinate `at` holds first: the lower face holds the rows at or
  /// below it, the upper face those at or above it (within 1e-6 dx). A face between rows thus
  /// acts at the row beyond it; the cull box and the scene reader's note follow this.
  static long faceRow(double at, double dx, bool upper) {
    return upper ? long(std::ceil(at / dx - 1e-6)) : long(std::floor(at / dx + 1e-6));
  }

  const std::string& name() const { return name_; }
  const ContactLaw& law() const { return *law_; }
  /// A panel: a window of a domain face (Collider::panel).
  bool isPanel() const { return windowed_; }
  /// A face or panel's outward normal axis and side: the material pushes along +axis on the
  /// upper face. -1 for a solid.
  int faceAxis() const { return axis_; }
  bool faceUpper() const { return upper_; }
  /// A panel's area on the face: the tributary area of the node rows and columns it takes
  /// (dx each, half at the domain's edge, which [lo, hi], the domain box in the local frame,
  /// bounds). A node row of a face between two walls d apart has area dx d, so a still water's
  /// pressure on it is its load over this area. 0 for anything but a panel.
  double panelArea(double dx, const Vec3d& lo, const Vec3d& hi) const;
  bool moves() const { return motion_.moves(); }
  /// Reference point of the moments at time t (local frame).
  Vec3d reference(double t) const;

  /// Before the grid update of a step ending at time t: caches the geometry of newly active
  /// blocks (at rest) or the pose (moving).
  void prepare(const BlockTopology& topology, double dx, double t);
  /// The nodes of block b (coordinate c) inside the collider, with normals and velocities.
  void gather(uint32_t b, const BlockCoord& c, double dx, const Vec4* nodes, ContactBatch& out) const;

  /// Law parameters that vary in space (a collider at rest only); null: the law's own everywhere.
  void setParameters(std::shared_ptr<const ParameterField> field) { params_ = std::move(field); }
  /// Whether the solid may keep only the part around the active blocks (Sdf::focus; default
  /// true). False when something else queries it anywhere during the run.
  void setFocusSolid(bool focus) { focusSolid_ = focus; }

  size_t memoryBytes() const {
    return (cache_ ? cache_->memoryBytes() + blocks_.capacity() * sizeof(void*) : 0) +
           paramCache_.size() * kBlockNodes * (params_ ? size_t(params_->count()) * sizeof(float) : 0);
  }

private:
  Collider(std::string name, std::shared_ptr<const ContactLaw> law) : name_(std::move(name)), law_(std::move(law)) {}
  void gatherFace(const BlockCoord& c, double dx, const Vec4* nodes, ContactBatch& out) const;
  void gatherMoving(const BlockCoord& c, double dx, const Vec4* nodes, ContactBatch& out) const;

  std::string name_;
  std::shared_ptr<const ContactLaw> law_;
  // A face of the box.
  int axis_ = -1;
  bool upper_ = false;
  double at_ = 0;
  bool windowed_ = false;                 ///< a panel: only the nodes within [windowLo_, windowHi_]
  Vec3d windowLo_ = Vec3d::Zero(), windowHi_ = Vec3d::Zero();
  // A solid.
  std::shared_ptr<const Sdf> sdf_;
  ColliderMotion motion_;
  Vec3d reference_ = Vec3d::Zero();
  std::unique_ptr<SdfCache> cache_;       ///< at rest: phi and normals per block, sampled once
  bool focusSolid_ = true;
  std::vector<const SdfBlock*> blocks_;   ///< at rest: per active block, its cache or null
  std::shared_ptr<const ParameterField> params_;
  std::unordered_map<uint64_t, std::vector<float>> paramCache_; ///< per block key: count() per node
  std::vector<const float*> paramBlocks_;                       ///< per active block, or null
  Vec3d restLo_, restHi_;                 ///< moving: bounds of the rest geometry
  Mat3d R_ = Mat3d::Identity();           ///< moving: pose this step
  Vec3d d_ = Vec3d::Zero();
  double time_ = 0;
};

} // namespace talus
