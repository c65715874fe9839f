// Line features with elevations from a vector file (shapefile, GeoJSON, GeoPackage... anything
// OGR reads): AvaFrame's DAM/ lines, whose vertices carry the crest elevation as z, with a
// numeric attribute per feature (the dam's `slope`).
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

namespace talus {

struct LineFeature {
  std::vector<Eigen::Vector3d> points; ///< world x, y and the vertex's z (NaN when the file has none)
  double value = NAN;                  ///< the attribute's value (NaN when absent or null)
};

/// Every LineString (and each part of a MultiLineString) of the first layer, repeated vertices
/// dropped, with `attribute` when given. Throws InputError naming the file: missing, unreadable,
/// no line of two distinct points.
std::vector<LineFeature> readLineFeatures(const std::string& path, const std::string& attribute = "");

} // namespace talus
