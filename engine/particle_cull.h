// The cull: particles that left the domain are removed, their mass reported per material.
//
// A closed face constrains the nodes on or beyond its plane (Collider::face), so the wall the
// material meets is the first such node row, up to a cell beyond a plane that falls between
// nodes. Particles are kept up to half a cell past that row; at an open face, up to the plane.
// (Culling half a cell past the plane itself removed particles pressed against a wall before they
// reached it: 0.75 % of the water in the Buchner impact at H/dx = 20, whose far wall stands 0.68
// cells short of a node row.) Periodic axes wrap instead.
#pragma once

#include "engine/contact_law.h"
#include "engine/material_group.h"
#include "engine/periodic.h"

#include <array>
#include <memory>

namespace talus {

struct CullBox {
  Vec3 lo, hi; ///< particles outside [lo, hi] (local frame) are removed
};

/// The box a scene keeps its particles in: `faces` null where a face is open (in the order of
/// faceNames()), unbounded along periodic axes.
CullBox cullBox(const DomainBox& domain, const std::array<std::shared_ptr<const ContactLaw>, 6>& faces,
                const Periodicity& periodic, double dx);

/// Wraps the group's particles along periodic axes, then removes those outside `box` (order of the
/// rest kept). Returns the mass removed (kg).
double cullOutside(MaterialGroup& group, const CullBox& box, const Periodicity& periodic, Real dx);

} // namespace talus
