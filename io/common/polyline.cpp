#include "io/common/polyline.h"

#include "io/common/input_error.h"

#include <algorithm>
#include <cmath>
#include <cpl_conv.h>
#include <cpl_error.h>
#include <cstdlib>
#include <filesystem>
#include <gdal_priv.h>
#include <limits>
#include <memory>
#include <ogrsf_frmts.h>
#include <sstream>
#include <stdexcept>

namespace talus {

Polyline::Polyline(std::vector<Eigen::Vector2d> points) : pts_(std::move(points)) {
  if (pts_.size() < 2) throw std::invalid_argument("a polyline needs at least two points");
  cum_.assign(1, 0.0);
  for (size_t k = 1; k < pts_.size(); ++k) {
    const double d = (pts_[k] - pts_[k - 1]).norm();
    if (!(d > 0)) throw std::invalid_argument("a polyline repeats a point");
    cum_.push_back(cum_.back() + d);
  }
}

Polyline Polyline::parse(const std::string& spec) {
  if (spec.find(',') != std::string::npos && !std::filesystem::exists(spec)) {
    std::vector<Eigen::Vector2d> pts;
    std::istringstream in(spec);
    std::string tok;
    while (in >> tok) {
      const auto comma = tok.find(',');
      char* end1 = nullptr;
      char* end2 = nullptr;
      const std::string a = tok.substr(0, comma), b = comma == std::string::npos ? "" : tok.substr(comma + 1);
      const double x = std::strtod(a.c_str(), &end1), y = std::strtod(b.c_str(), &end2);
      if (comma == std::string::npos || a.empty() || b.empty() || *end1 || *end2 || !std::isfinite(x) ||
          !std::isfinite(y))
        throw std::invalid_argument("'" + tok + "' is not a point x,y (a line is \"x,y x,y ...\")");
      pts.emplace_back(x, y);
    }
    return Polyline(std::move(pts));
  }
  if (!std::filesystem::exists(spec)) throw InputError(spec, "file not found (or give the line as \"x,y x,y ...\")");
  GDALAllRegister();
  CPLPushErrorHandler(CPLQuietErrorHandler);
  GDALDataset* ds = GDALDataset::Open(spec.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY);
  CPLPopErrorHandler();
  if (!ds) throw InputError(spec, "not a vector file GDAL/OGR can read");
  std::unique_ptr<GDALDataset, void (*)(GDALDataset*)> hold(ds, [](GDALDataset* d) { GDALClose(GDALDataset::ToHandle(d)); });
  std::vector<Eigen::Vector2d> pts;
  for (int l = 0; l < ds->GetLayerCount() && pts.empty(); ++l) {
    OGRLayer* layer = ds->GetLayer(l);
    layer->ResetReading();
    for (auto& feat : *layer) {
      const OGRGeometry* geom = feat->GetGeometryRef();
      if (!geom) continue;
      const auto type = wkbFlatten(geom->getGeometryType());
      const OGRLineString* line = nullptr;
      if (type == wkbLineString) line = geom->toLineString();
      else if (type == wkbMultiLineString && geom->toMultiLineString()->getNumGeometries() > 0)
        line = geom->toMultiLineString()->getGeometryRef(0);
      if (!line) continue;
      for (int i = 0; i < line->getNumPoints(); ++i) {
        const Eigen::Vector2d p(line->getX(i), line->getY(i));
        if (pts.empty() || (p - pts.back()).norm() > 0) pts.push_back(p);
      }
      break;
    }
  }
  if (pts.size() < 2) throw InputError(spec, "no line feature with two distinct points");
  return Polyline(std::move(pts));
}

Eigen::Vector2d Polyline::at(double s) const {
  s = std::clamp(s, 0.0, length());
  size_t k = 0;
  while (k + 2 < pts_.size() && cum_[k + 1] < s) ++k;
  const double t = (s - cum_[k]) / (cum_[k + 1] - cum_[k]);
  return pts_[k] + t * (pts_[k + 1] - pts_[k]);
}

double Polyline::nearest(const Eigen::Vector2d& p, bool openEnds, double& along, double& offset, bool& beyond) const {
  double best = std::numeric_limits<double>::infinity();
  along = offset = 0;
  beyond = false;
  const size_t nseg = pts_.size() - 1;
  for (size_t k = 0; k < nseg; ++k) {
    const Eigen::Vector2d a = pts_[k], d = pts_[k + 1] - a;
    const double len = cum_[k + 1] - cum_[k];
    const Eigen::Vector2d u = d / len, r = p - a;
    const double t = r.dot(u);
    const bool out = (t < 0 && k == 0) || (t > len && k + 1 == nseg);
    if (out && openEnds) continue;
    const double tc = std::clamp(t, 0.0, len);
    const double dist = (r - tc * u).norm();
    if (dist < best) {
      best = dist, along = cum_[k] + tc, offset = u.x() * r.y() - u.y() * r.x();
      beyond = out;
      if (out) offset = (offset < 0 ? -1 : 1) * dist;
    }
  }
  return best;
}

double Polyline::project(const Eigen::Vector2d& p, double* offset, bool* beyond) const {
  double s, off;
  bool out;
  nearest(p, false, s, off, out);
  if (offset) *offset = off;
  if (beyond) *beyond = out;
  return s;
}

double Polyline::nearestWithin(const Eigen::Vector2d& p, double& along, double& offset) const {
  bool out;
  return nearest(p, true, along, offset, out);
}

} // namespace talus
