// Solids as signed distances: the union of several (phi = min over the parts; fixed regions of a
// scene are added to the DEM's level set this way), and analytic shapes.
#pragma once

#include "engine/sdf.h"
#include "engine/shapes.h"

#include <memory>
#include <string>
#include <vector>

namespace talus {

class UnionSdf final : public Sdf {
public:
  explicit UnionSdf(std::vector<std::shared_ptr<const Sdf>> parts) : parts_(std::move(parts)) {}
  /// Per node the part with the smallest phi wins (its phi and normal). Parts reporting no
  /// ground in a block are skipped: their phi there is positive, which never decides a contact.
  bool sampleBlock(const BlockCoord& c, double dx, SdfBlock& out) const override;
  double distance(const Vec3d& x) const override;
  std::string describe() const override;
  size_t residentBytes() const override {
    size_t b = 0;
    for (const auto& p : parts_) b += p->residentBytes();
    return b;
  }
  void focus(const BlockCoord& lo, const BlockCoord& hi, double dx) const override {
    for (const auto& p : parts_) p->focus(lo, hi, dx);
  }

private:
  std::vector<std::shared_ptr<const Sdf>> parts_;
};

/// An analytic solid (engine/shapes.h) as a signed distance; blocks are sampled node by node,
/// normals by central differences of the distance at +-dx/4.
class ShapeSdf final : public Sdf {
public:
  ShapeSdf(std::shared_ptr<const Shape> shape, std::string description)
      : shape_(std::move(shape)), description_(std::move(description)) {}
  double distance(const Vec3d& x) const override { return shape_->distance(x); }
  void bounds(Vec3d& lo, Vec3d& hi) const override { shape_->bounds(lo, hi); }
  std::string describe() const override { return description_; }
  const Shape& shape() const { return *shape_; }

private:
  std::shared_ptr<const Shape> shape_;
  std::string description_;
};

} // namespace talus
