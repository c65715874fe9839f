#include "io/terrain/line_features.h"

#include "io/common/input_error.h"

#include <gdal_priv.h>
#include <ogrsf_frmts.h>

#include <cmath>
#include <filesystem>
#include <memory>

namespace talus {

std::vector<LineFeature> readLineFeatures(const std::string& path, const std::string& attribute) {
  if (!std::filesystem::exists(path)) throw InputError(path, "file not found");
  GDALAllRegister();
  CPLPushErrorHandler(CPLQuietErrorHandler);
  GDALDataset* ds = GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY);
  CPLPopErrorHandler();
  if (!ds || ds->GetLayerCount() < 1) throw InputError(path, "not a vector file GDAL/OGR can read");
  std::unique_ptr<GDALDataset, void (*)(GDALDataset*)> hold(ds, [](GDALDataset* d) { GDALClose(GDALDataset::ToHandle(d)); });
  OGRLayer* layer = ds->GetLayer(0);
  std::vector<LineFeature> out;
  for (auto& feat : *layer) {
    const OGRGeometry* geom = feat->GetGeometryRef();
    if (!geom) continue;
    std::vector<const OGRLineString*> parts;
    const auto type = wkbFlatten(geom->getGeometryType());
    if (type == wkbLineString) parts.push_back(geom->toLineString());
    if (type == wkbMultiLineString)
      for (const OGRGeometry* g : *geom->toMultiLineString()) parts.push_back(g->toLineString());
    double value = NAN;
    if (!attribute.empty()) {
      const int f = feat->GetFieldIndex(attribute.c_str());
      if (f >= 0 && feat->IsFieldSetAndNotNull(f)) value = feat->GetFieldAsDouble(f);
    }
    for (const OGRLineString* line : parts) {
      LineFeature lf;
      lf.value = value;
      for (int i = 0; i < line->getNumPoints(); ++i) {
        const Eigen::Vector3d p(line->getX(i), line->getY(i), line->Is3D() ? line->getZ(i) : NAN);
        if (lf.points.empty() || (p.head<2>() - lf.points.back().head<2>()).norm() > 0) lf.points.push_back(p);
      }
      if (lf.points.size() >= 2) out.push_back(std::move(lf));
    }
  }
  if (out.empty()) throw InputError(path, "no line feature with two distinct points");
  return out;
}

} // namespace talus
