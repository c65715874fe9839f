// Is every file in an output folder whole? For the fault tests and the soak tool: a run killed
// or failing at any instant must leave no half-written file behind.
#pragma once

#include <string>
#include <vector>

namespace talus {

/// Reads every file below `dir` with the library that reads its kind (HDF5 particles, the
/// checkpoint's checksum, OpenVDB grids, GeoTIFF rasters, PNG images, CSV rows against the
/// header, JSON closing brace, PLY vertex count) and returns one line per problem, e.g.
/// "frames/volume_00003.vdb: ..." or "series.csv.tmp: a temporary file left behind".
std::vector<std::string> incompleteOutputFiles(const std::string& dir);

} // namespace talus
