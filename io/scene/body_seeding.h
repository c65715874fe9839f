// Filling [[bodies]] with particles: solids (box, sphere, cylinder) and bodies on the terrain
// (releases, layers, water), with a report of what each seeded.
#pragma once

#include "engine/material_group.h"
#include "engine/secondary_release.h"
#include "engine/shapes.h"
#include "io/config/config_table.h"
#include "io/scene/particle_seeding.h"
#include "io/terrain/terrain_bodies.h"

#include <string>
#include <vector>

namespace talus {

struct BodyReport {
  std::string label;    ///< "bodies[i]" or the body's name
  std::string material;
  std::string kind;
  size_t particles = 0;
  double seededVolume = 0;    ///< particles * dx^3 / ppc
  double geometricVolume = 0; ///< of the shape (before terrain clipping)
  double meanThickness = 0;   ///< terrain bodies: vertical, volume / plan area (m); 0 otherwise
  int particlesPerCell = 0;   ///< terrain bodies: the seeding's (the body's own or the scene's)
  double fieldMass = 0;       ///< a cover made an erodible field (no particles): its mass (kg)
  /// Terrain bodies with match_volume (releases by default): the factor the particles' masses
  /// were scaled by so that the body holds geometricVolume; 1 when not scaled.
  double massScale = 1;
};

/// Below this many cells across its mean thickness a released body's peak flow heights lose
/// accuracy (docs/convergence.md, "Thin releases").
constexpr double kThinBodyCells = 1.0;

/// A body with `trigger_thickness` (m) is a secondary release: its particles, seeded into `group`
/// (at `position` among the scene's groups) from index `first` on, leave the group for a HeldBody (engine/secondary_release.h) that joins
/// it when the flow over it weighs as much per area as that thickness of the body's material.
/// Returns whether it held the body. Throws InputError on a trigger that is not positive.
bool holdSecondaryRelease(const ConfigTable& t, const std::string& label, MaterialGroup& group, int position,
                          size_t first, std::vector<HeldBody>& held);

/// A warning for a terrain body thinner than kThinBodyCells at grid spacing dx, else "".
std::string thinBodyNote(const BodyReport& body, double dx);

/// Seeds a solid body (its table `t` gives velocity and angular_velocity) into `group`, inside the
/// domain [domainMin, domainMax] (local). Throws InputError naming the table's keys.
BodyReport seedShapeBody(const ConfigTable& t, const Shape& shape, const SeedSpec& spec, const Vec3d& domainMin,
                         const Vec3d& domainMax, MaterialGroup& group);

/// Seeds a terrain body (or, for fixed regions, only measures it). `bed` is the ground the bodies
/// lie on; spec.terrain the final terrain (samples inside it are skipped), and so are samples
/// inside the `earlier` terrain bodies: where they overlap, the first body wins. Domain bounds
/// are world coordinates here.
BodyReport seedTerrainBody(const TerrainBody& body, const HeightField& bed, const SeedSpec& spec, const Vec3d& origin,
                           const Vec3d& domainMin, const Vec3d& domainMax, MaterialGroup* group,
                           const std::vector<const TerrainBody*>& earlier);

} // namespace talus
