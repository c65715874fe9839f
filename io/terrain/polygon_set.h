// Polygons from a vector file (shapefile, GeoJSON, GeoPackage... anything OGR reads): the
// outlines of release areas, snow covers, reservoirs and fixed regions, in the DEM's CRS.
#pragma once

#include "io/common/input_error.h"

#include <string>
#include <vector>

namespace talus {

class PolygonSet {
public:
  /// Reads every polygon and multipolygon feature of the first layer (or of `layer`). When
  /// `attribute` is given, each feature's value of that numeric field is kept (missing/null is
  /// an error). Throws InputError naming the file (missing, unreadable, no polygon, no field).
  static PolygonSet read(const std::string& path, const std::string& attribute = "", const std::string& layer = "");
  /// An axis-aligned rectangle (for bodies given `bounds` instead of a polygon).
  static PolygonSet rectangle(double xmin, double ymin, double xmax, double ymax);

  /// Index of the first feature containing (x, y) (holes excluded), or -1. Fast: edges are
  /// bucketed by y, so a query looks at the few edges crossing its row.
  int locate(double x, double y) const;
  bool contains(double x, double y) const { return locate(x, y) >= 0; }
  double value(int feature) const { return values_[size_t(feature)]; }
  size_t features() const { return values_.size(); }
  /// Planar area (m^2) of the union of the features' interiors (features assumed disjoint).
  double area() const { return area_; }
  void bounds(double& xmin, double& ymin, double& xmax, double& ymax) const {
    xmin = xmin_, ymin = ymin_, xmax = xmax_, ymax = ymax_;
  }
  const std::string& crsWkt() const { return crsWkt_; }
  const std::string& path() const { return path_; }

private:
  struct Edge {
    double x0, y0, x1, y1;
    int feature;
  };
  void index();
  std::vector<Edge> edges_;
  std::vector<double> values_;
  std::vector<std::vector<int>> buckets_; ///< edges crossing each y bucket, sorted by feature
  double xmin_ = 0, ymin_ = 0, xmax_ = 0, ymax_ = 0, bucketH_ = 1, area_ = 0;
  std::string crsWkt_, path_;
};

} // namespace talus
