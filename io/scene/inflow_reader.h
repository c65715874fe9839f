// [[inflows]]: material entering through a cross-section with a hydrograph (engine/inflow_source.h):
//
//   [[inflows]]
//   name = "torrent"
//   material = "debris"
//   section = [[x0, y0], [x1, y1]]      # across the channel (world); entry on its left unless
//   direction = [dx, dy]               # given: horizontal, normalised
//   hydrograph = "torrent.csv"          # time_s, discharge_m3_s[, speed_m_s] with a header row,
//                                       # or inline [[t, Q], ...] / [[t, Q, v], ...]
//   speed = 4.0                         # m/s, when the hydrograph has no speed column
#pragma once

#include "io/config/config_table.h"
#include "io/scene/scene.h"

namespace talus {

/// Appends one InflowSource per [[inflows]] table to s.settings.sources (after the terrain: the
/// section's slots sit on it). Throws InputError naming the file, line and key: an unknown
/// material, a section of other than two points or shorter than a particle spacing, a hydrograph
/// file that cannot be read or has a bad row (its line named), times not increasing, negative
/// discharge, no speed.
void readInflows(const ConfigTable& root, SceneSetup& s);

} // namespace talus
