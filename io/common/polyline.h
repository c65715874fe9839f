// A polyline in world (or local) xy with the distance along it: paths, profiles, the AIMEC
// thalweg. Read from "x,y x,y ..." text or the first line of a vector file.
#pragma once

#include <Eigen/Dense>
#include <string>
#include <vector>

namespace talus {

/// A polyline in world xy with the distance along it.
class Polyline {
public:
  Polyline() = default;
  explicit Polyline(std::vector<Eigen::Vector2d> points);
  /// "x,y x,y ..." (at least two points), or a vector file GDAL/OGR reads whose first line
  /// feature (LineString, or the first part of a MultiLineString) is the polyline. Throws
  /// InputError (file) or std::invalid_argument (text).
  static Polyline parse(const std::string& spec);

  const std::vector<Eigen::Vector2d>& points() const { return pts_; }
  double length() const { return cum_.empty() ? 0 : cum_.back(); }
  /// The point at distance s along the line (clamped to its ends).
  Eigen::Vector2d at(double s) const;
  /// Nearest point of the line to p: distance along it and the perpendicular offset (left of
  /// the direction of travel positive). Points beyond either end project onto the end with
  /// `beyond` set.
  double project(const Eigen::Vector2d& p, double* offset = nullptr, bool* beyond = nullptr) const;
  /// The nearest point among those p projects onto perpendicularly (beyond the two ends the line
  /// is not extended): its distance from p (infinite when there is none), with the distance
  /// along the line and the signed offset as `project` gives them.
  double nearestWithin(const Eigen::Vector2d& p, double& along, double& offset) const;

private:
  /// Nearest point over all segments; with `openEnds` the parts beyond the end points are left out.
  double nearest(const Eigen::Vector2d& p, bool openEnds, double& along, double& offset, bool& beyond) const;
  std::vector<Eigen::Vector2d> pts_;
  std::vector<double> cum_;
};

} // namespace talus
