// A `[[bodies]]` layer thinner than its `field_below` becomes an erodible field on the terrain
// (engine/erodible_bed.h) instead of particles: its mass per grid node column, AvaFrame's erosion
// energy, and the mass of the particles the eroded snow becomes.
//
//   [[bodies]]
//   kind = "layer"            # with a polygon, bounds, or the whole domain, as any layer
//   material = "snow"         # the cover's material: eroded mass joins the flow as its particles
//   thickness = 0.3
//   field_below = 5.0         # m: a field when the mean (vertical) thickness is below; default dx
//   erosion_energy = 5000     # J/kg: AvaFrame's entEroEnergy (its default)
#pragma once

#include "engine/erodible_bed.h"
#include "io/scene/body_seeding.h"

#include <optional>

namespace talus {

/// When `body` is a layer thinner (mean vertical thickness) than its table's `field_below`
/// (default: dx), its cover as a field: a column at every grid node (i dx, j dx) of the local
/// frame inside it, holding rho x (its vertical thickness there) x dx^2, none where an `earlier`
/// body (a release) lies on the ground (AvaFrame crops entrainment areas by release areas).
/// Otherwise nullopt, and the body is seeded as particles. `rep` gets the body's measures.
/// Throws InputError (a key of the body's table) for a cover with no column or a bad value.
std::optional<ErodibleCover> readErodibleCover(const TerrainBody& body, const HeightField& bed, const Vec3d& origin,
                                               double dx, int particlesPerCell, const MaterialGroup& group,
                                               int groupPosition, const std::vector<const TerrainBody*>& earlier,
                                               BodyReport& rep);

/// The line the scene's notes give a cover made a field.
std::string erodibleCoverNote(const ErodibleCover& cover, const BodyReport& rep, double dx);

} // namespace talus
