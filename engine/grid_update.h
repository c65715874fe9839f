// Grid update: momentum to velocity, gravity and damping on every active node, then each
// collider's contact law on the nodes inside it, with the load each collider takes.
#pragma once

#include "engine/collider.h"
#include "engine/flow_thickness.h"
#include "engine/sparse_grid.h"

#include <vector>

namespace talus {

/// A material's own basal law: it replaces every collider's law for that material's share of a
/// node's mass, read from P2G's extra channel `channel` (the material's node mass).
struct MaterialLaw {
  int channel = 0;
  const ContactLaw* law = nullptr;
};

struct GridUpdateParams {
  Real dt = 0;
  Vec3 gravity = Vec3::Zero();
  Real damping = 0; ///< velocity damping rate (1/s), see SimulationSettings::damping
  /// Where materials share a contact node, the velocity is the mass-weighted mean of each law's
  /// result (the collider's law for the materials without their own).
  std::vector<MaterialLaw> const* materialLaws = nullptr; ///< null or empty: colliders' laws only
  /// Per active block, whether its loads count here (MPI ranks: engine/halo_exchange.h); null: all.
  std::vector<uint8_t> const* counted = nullptr;
  /// Erodible covers (engine/erodible_bed.h): per node of every block, the basal work (J) the
  /// first collider's law did this step, |tangential impulse| x sliding speed after it; null: none.
  float* basalWork = nullptr;
};

/// After this, node records hold (mass, velocity). Colliders act in list order on each node.
/// loads[k] receives collider k's load of this step; the per-block sums are added in block order,
/// so loads are bit-identical at any thread count.
/// `columns` (may be null when no law needs it) gives laws the flow thickness.
void updateGridVelocities(SparseGrid& grid, const GridUpdateParams& params, const std::vector<Collider*>& colliders,
                          double time, const FlowColumns* columns, std::vector<ColliderLoad>& loads);

} // namespace talus
