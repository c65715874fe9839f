// The [avaframe] section (or `--avaframe DIR`): an AvaFrame avalanche folder becomes part of the
// scene. The folder says where (DEM, release and entrainment areas, the AIMEC path); the scene
// says what AvaFrame does not: materials, dx, end time, the basal law. docs/hazard.md has the
// mapping:
//
//   Inputs/<DEM>   -> [terrain] dem (fill_nodata defaults to true; a DEM without CRS takes the
//                     shapefiles' CRS, AvaFrame's one-projection rule)
//   REL/<scenario> -> a [[bodies]] release of release_material, thickness per feature from the
//                     `thickness` attribute (or release_thickness, AvaFrame's relTh), slope-normal
//   ENT/           -> a [[bodies]] layer of entrainment_material (an erodible cover), thickness
//                     from the attribute, else entrainment_thickness, else AvaFrame's 0.3 m;
//                     left out (AvaFrame's "null" simulation) when entrainment_material is not set
//   RES/           -> read and validated as regions (resistanceRegions), not yet applied
//   output         -> hazard maps and AvaFrame peak files (peakFiles/) on unless switched off
#pragma once

#include "io/config/config_table.h"

#include <string>
#include <vector>

namespace talus {

/// Expands root's [avaframe] table, if any, into [terrain], [[bodies]] (placed before the
/// scene's own bodies, so a release keeps the space an entrainment cover shares with it) and
/// [output] defaults. Adds one note per input found but not applied. Throws InputError.
void expandAvaFrame(ConfigTable& root, std::vector<std::string>& notes);

/// `--avaframe DIR` as an override: the folder, absolute, in [avaframe] directory.
std::string avaFrameOverride(const std::string& dir);

} // namespace talus
