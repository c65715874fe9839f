// A dam along a polyline, as AvaFrame's DAM/ lines describe one: the line's vertices carry the
// crest elevation (linear between them), the flanks fall at `slope` degrees from the horizontal on
// both sides of a crest `width` wide, down to a base elevation per vertex (below the ground, so
// the terrain hides it). The cross-section at the plan point's nearest point of the line is the
// trapezoid
//
//   base <= z <= crest,  |d| <= width / 2 + (crest - z) / tan(slope)
//
// (d the horizontal offset from the line); beyond the line's ends the dam ends in a vertical cut.
// The signed distance is that of the cross-section (exact across the dam, an approximation within
// a flank's width of a bend, as for any swept solid).
#pragma once

#include "engine/sdf.h"

#include <string>
#include <vector>

namespace talus {

class DamSdf final : public Sdf {
public:
  struct Vertex {
    double x = 0, y = 0; ///< local frame
    double crest = 0, base = 0;
  };
  /// At least two vertices (distinct in plan), crest > base at each, 0 < slopeDeg <= 90,
  /// width >= 0. Throws std::invalid_argument otherwise.
  DamSdf(std::vector<Vertex> line, double slopeDeg, double width, std::string description);
  double distance(const Vec3d& x) const override;
  void bounds(Vec3d& lo, Vec3d& hi) const override;
  std::string describe() const override { return description_; }

private:
  std::vector<Vertex> v_;
  double cot_, halfWidth_;
  std::string description_;
};

} // namespace talus
