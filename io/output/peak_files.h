// AvaFrame peak files: the hazard maps under the names and in the layout AvaFrame's own tools
// (ana3AIMEC, ana4Stats probAna) read, following com1DFA from version 1.11 to the 2025-11-06
// snapshot (commit 21e4b944; docs/moduleCom1DFA.rst "Output", in3Utils/cfgUtils.parseSimName):
//
//   peakFiles/<release>_<simHash>_C_L_<simType>_mpm_<resType>.asc (or .tif)
//
//   release   release scenario name; one containing '_' gets AvaFrame's "_AF" suffix
//   simHash   10 hex digits naming the configuration (here: of the scene, overrides included)
//   C         a custom configuration (AvaFrame's D is its default setup)
//   L         AvaFrame's friction-calibration indicator: S and M only for samosATSmall/Medium
//   simType   null (releases only) or ent (with erodible covers); res is not written yet
//   mpm       the model type (AvaFrame: dfa for its dense-flow model; any word is allowed)
//   resType   pft  peak flow thickness, slope-normal (m)
//             pfv  peak flow velocity (m/s)
//             ppr  peak pressure rho v^2 (kPa)
//             pfd  peak flow depth measured vertically (m): not an AvaFrame type since 1.1,
//                  when AvaFrame renamed its pfd (then slope-normal) to pft
//
// Rasters are on the DEM's grid (no data -9999), or with peak_file_grid = "com1dfa" on com1DFA's
// mesh (no data NaN), in the DEM's format unless peak_file_format says otherwise.
#pragma once

#include "io/common/raster_grid.h"
#include "io/output/output_settings.h"

#include <string>
#include <vector>

namespace talus {

/// "<release>_<simHash>_C_L_<simType>_mpm": AvaFrame's simName.
std::string avaFrameSimName(const PeakFileSettings& s);

/// The AvaFrame result types Talus writes, in order: pft, pfv, ppr, pfd.
const std::vector<std::string>& peakResultTypes();

/// com1DFA's output mesh for a DEM grid: the DEM's first (south-west) cell centre kept, cells of
/// `meshCellSize`, floor((n - 1) dx_dem / meshCellSize) + 1 of them per axis (avaWog's 490 x 555
/// cells of 4.99768 m give com1DFA's 489 x 554 of 5 m).
RasterGrid com1dfaGrid(const RasterGrid& dem, double meshCellSize);

/// `values` on `from` (cell-centred, `nodata` where none) at the cell centres of `onto`:
/// bilinear where the four surrounding centres have data, else the nearest centre's value, NaN
/// outside `from` or without data.
std::vector<float> resampleCentres(const RasterGrid& from, const std::vector<float>& values, float nodata,
                                   const RasterGrid& onto);

/// Writes one file per result type (values[i] for peakResultTypes()[i]) into outDir/peakFiles in
/// `format` ("asc", "tif" or "both"); returns the paths relative to outDir.
std::vector<std::string> writePeakFiles(const std::string& outDir, const PeakFileSettings& s, const std::string& format,
                                        const RasterGrid& grid, const std::vector<std::vector<float>>& values,
                                        float nodata);

} // namespace talus
