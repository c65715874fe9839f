// [[structures]]: dams, walls, gallery roofs, gates in the flow. Each is a collider with a
// geometry (a box, cylinder or sphere, or a .vdb level set), a contact law and an optional
// prescribed motion, motion = { velocity, angular_velocity, pivot, start, stop }; the loads the
// material puts on it are written to series.csv.
#pragma once

#include "engine/simulation.h"
#include "io/config/config_table.h"

#include <string>
#include <vector>

namespace talus {

/// Reads every [[structures]] table into settings.structures (local frame via settings.origin).
/// `notes` receives warnings a user should see (a structure thinner than two cells leaks).
void readStructures(const ConfigTable& root, SimulationSettings& settings, std::vector<std::string>& notes);

} // namespace talus
