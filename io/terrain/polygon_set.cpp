#include "io/terrain/polygon_set.h"

#include "io/terrain/dem_raster.h"

#include <algorithm>
#include <cmath>
#include <cpl_conv.h>
#include <cpl_error.h>
#include <filesystem>
#include <gdal_priv.h>
#include <memory>
#include <ogrsf_frmts.h>

namespace talus {

namespace {
struct QuietGdal {
  QuietGdal() { CPLPushErrorHandler(CPLQuietErrorHandler); CPLErrorReset(); }
  ~QuietGdal() { CPLPopErrorHandler(); }
};
constexpr double kMaxCoordinate = 1e9; // beyond any projected CRS on Earth
struct DatasetCloser {
  void operator()(GDALDataset* d) const { GDALClose(GDALDataset::ToHandle(d)); }
};
} // namespace

PolygonSet PolygonSet::read(const std::string& path, const std::string& attribute, const std::string& layerName) {
  if (!std::filesystem::exists(path)) throw InputError(path, "file not found");
  if (!std::filesystem::is_regular_file(path)) throw InputError(path, "not a regular file");
  GDALAllRegister();
  QuietGdal quiet;
  std::unique_ptr<GDALDataset, DatasetCloser> ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  if (!ds) throw InputError(path, "not a vector file GDAL/OGR can read (" + std::string(CPLGetLastErrorMsg()) + ")");
  OGRLayer* layer = layerName.empty() ? (ds->GetLayerCount() > 0 ? ds->GetLayer(0) : nullptr)
                                      : ds->GetLayerByName(layerName.c_str());
  if (!layer) throw InputError(path, (layerName.empty() ? "no layer" : "no layer named '" + layerName + "'"));
  PolygonSet ps;
  ps.path_ = path;
  if (const OGRSpatialReference* srs = layer->GetSpatialRef()) {
    char* wkt = nullptr;
    srs->exportToWkt(&wkt);
    ps.crsWkt_ = wkt ? wkt : "";
    CPLFree(wkt);
  }
  int field = -1;
  if (!attribute.empty()) {
    field = layer->GetLayerDefn()->GetFieldIndex(attribute.c_str());
    if (field < 0) {
      std::string names;
      for (int i = 0; i < layer->GetLayerDefn()->GetFieldCount(); ++i)
        names += (names.empty() ? "" : ", ") + std::string(layer->GetLayerDefn()->GetFieldDefn(i)->GetNameRef());
      throw InputError(path, "no attribute '" + attribute + "' (attributes: " + (names.empty() ? "none" : names) + ")");
    }
    // A text field would read as 0 everywhere: a thickness silently lost.
    const OGRFieldType type = layer->GetLayerDefn()->GetFieldDefn(field)->GetType();
    if (type != OFTReal && type != OFTInteger && type != OFTInteger64)
      throw InputError(path, "attribute '" + attribute + "' is a " + OGRFieldDefn::GetFieldTypeName(type) +
                                 " field, not a number");
  }
  layer->ResetReading();
  for (auto& feat : *layer) {
    const OGRGeometry* geom = feat->GetGeometryRef();
    if (!geom) continue;
    const auto type = wkbFlatten(geom->getGeometryType());
    std::vector<const OGRPolygon*> polys;
    if (type == wkbPolygon) polys.push_back(geom->toPolygon());
    else if (type == wkbMultiPolygon)
      for (const auto* p : *geom->toMultiPolygon()) polys.push_back(p);
    else continue;
    double v = 0;
    const std::string which = "feature " + std::to_string(feat->GetFID());
    if (field >= 0) {
      if (!feat->IsFieldSetAndNotNull(field)) throw InputError(path, which + " has no value for '" + attribute + "'");
      v = feat->GetFieldAsDouble(field);
      if (!std::isfinite(v)) throw InputError(path, which + ": '" + attribute + "' is not a finite number");
    }
    const int fi = int(ps.values_.size());
    ps.values_.push_back(v);
    for (const OGRPolygon* poly : polys) {
      ps.area_ += poly->get_Area();
      for (const auto* ring : *poly) {
        const int n = ring->getNumPoints();
        // A damaged file can hold NaN or infinite vertices; the edge index cannot bucket them.
        for (int k = 0; k < n; ++k)
          if (!std::isfinite(ring->getX(k)) || !std::isfinite(ring->getY(k)) || std::fabs(ring->getX(k)) > kMaxCoordinate ||
              std::fabs(ring->getY(k)) > kMaxCoordinate)
            throw InputError(path, which + " has a vertex that is not a finite coordinate below 1e9 m");
        for (int k = 0; k + 1 < n; ++k)
          ps.edges_.push_back({ring->getX(k), ring->getY(k), ring->getX(k + 1), ring->getY(k + 1), fi});
        if (n > 1 && (ring->getX(0) != ring->getX(n - 1) || ring->getY(0) != ring->getY(n - 1)))
          ps.edges_.push_back({ring->getX(n - 1), ring->getY(n - 1), ring->getX(0), ring->getY(0), fi});
      }
    }
  }
  if (ps.edges_.empty()) throw InputError(path, "no polygon features");
  ps.index();
  return ps;
}

PolygonSet PolygonSet::rectangle(double x0, double y0, double x1, double y1) {
  PolygonSet ps;
  ps.path_ = "bounds";
  ps.values_.push_back(0);
  ps.edges_ = {{x0, y0, x1, y0, 0}, {x1, y0, x1, y1, 0}, {x1, y1, x0, y1, 0}, {x0, y1, x0, y0, 0}};
  ps.area_ = (x1 - x0) * (y1 - y0);
  ps.index();
  return ps;
}

void PolygonSet::index() {
  xmin_ = ymin_ = INFINITY, xmax_ = ymax_ = -INFINITY;
  for (const Edge& e : edges_) {
    xmin_ = std::min({xmin_, e.x0, e.x1}), xmax_ = std::max({xmax_, e.x0, e.x1});
    ymin_ = std::min({ymin_, e.y0, e.y1}), ymax_ = std::max({ymax_, e.y0, e.y1});
  }
  const size_t nb = std::max<size_t>(1, std::min<size_t>(edges_.size(), 4096));
  bucketH_ = std::max((ymax_ - ymin_) / double(nb), 1e-9);
  buckets_.assign(nb, {});
  auto bucket = [&](double y) { return std::clamp(long(std::floor((y - ymin_) / bucketH_)), 0L, long(nb) - 1); };
  for (size_t i = 0; i < edges_.size(); ++i) {
    const Edge& e = edges_[i];
    if (e.y0 == e.y1) continue; // horizontal edges never cross a horizontal ray
    for (long b = bucket(std::min(e.y0, e.y1)); b <= bucket(std::max(e.y0, e.y1)); ++b) buckets_[size_t(b)].push_back(int(i));
  }
  for (auto& b : buckets_)
    std::stable_sort(b.begin(), b.end(), [&](int a, int c) { return edges_[size_t(a)].feature < edges_[size_t(c)].feature; });
}

int PolygonSet::locate(double x, double y) const {
  if (!(x >= xmin_ && x <= xmax_ && y >= ymin_ && y <= ymax_)) return -1;
  const long nb = long(buckets_.size());
  const long b = std::clamp(long(std::floor((y - ymin_) / bucketH_)), 0L, nb - 1);
  // Even-odd rule per feature on a ray towards +x; edges are half-open in y so a vertex is
  // counted once. Edges come sorted by feature.
  int current = -1;
  bool inside = false;
  for (int ei : buckets_[size_t(b)]) {
    const Edge& e = edges_[size_t(ei)];
    if (e.feature != current) {
      if (inside) return current;
      current = e.feature, inside = false;
    }
    if ((e.y0 > y) != (e.y1 > y)) {
      const double xc = e.x0 + (y - e.y0) * (e.x1 - e.x0) / (e.y1 - e.y0);
      if (xc > x) inside = !inside;
    }
  }
  return inside ? current : -1;
}

} // namespace talus
