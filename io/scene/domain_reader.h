// [domain]: the simulation's box (or a DEM's extent), its local origin, the faces' contact laws
// and periodic axes.
#pragma once

#include "io/config/config_table.h"
#include "io/scene/scene.h"

namespace talus {

struct DemTerrainInput;

/// Reads [domain] into s.settings (domain in the local frame, origin, faces, periodic axes); after
/// [simulation] (dx). `[domain]` may be omitted (or give only walls/origin) for a DEM terrain
/// (`dem` not null): the box then spans the DEM's extent and its elevations, 8 cells below the
/// lowest point and max(100 m, 20 cells) above the highest. Throws InputError naming the key (a
/// box that is empty or leaves the DEM, a periodic axis not of whole blocks). Adds to s.notes a
/// wall that lies between node rows.
void readDomain(const ConfigTable& root, SceneSetup& s, const DemTerrainInput* dem);

} // namespace talus
