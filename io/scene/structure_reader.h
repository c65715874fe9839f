// [[structures]]: dams, walls, gallery roofs, gates in the flow. Each is a collider with a
// geometry (a box, cylinder or sphere, or a .vdb level set), a contact law and an optional
// prescribed motion, motion = { velocity, angular_velocity, pivot, start, stop }; the loads the
// material puts on it are written to series.csv. [[panels]]: a part of a domain face with its
// own load columns (a pressure sensor on a flume wall).
#pragma once

#include "engine/simulation.h"
#include "io/config/config_table.h"

#include <string>
#include <vector>

namespace talus {

/// Reads every [[structures]] table into settings.structures (local frame via settings.origin).
/// `notes` receives warnings a user should see (a structure thinner than two cells leaks).
void readStructures(const ConfigTable& root, SimulationSettings& settings, std::vector<std::string>& notes);

/// Reads every [[panels]] table (a part of a closed domain face whose load is reported on its own:
/// a pressure sensor on a wall) into settings.panels; after the faces and structures are read.
void readPanels(const ConfigTable& root, SimulationSettings& settings);

} // namespace talus
