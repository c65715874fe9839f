// Helpers for the terrain tests: small rasters and polygons written with GDAL into temp dirs,
// and a level-set cache that does not touch the user's ~/.cache.
#pragma once

#include "io/terrain/dem_raster.h"
#include "test_support.h"

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <gdal_priv.h>
#include <ogrsf_frmts.h>
#include <string>
#include <utility>
#include <vector>

namespace talus::test {

/// Level sets built by the tests go to one shared temp dir (kept between tests: files are
/// written atomically, and reusing them is what the cache is for).
inline void useTestTerrainCache() {
  static const bool once = [] {
    const auto d = std::filesystem::temp_directory_path() / "talus_test_terrain_cache";
    std::filesystem::create_directories(d);
    setenv("TALUS_CACHE_DIR", d.c_str(), 1);
    return true;
  }();
  (void)once;
}

/// A DEM with heights f(x, y) at the cell centres; (west, south) is the south-west corner.
inline DemRaster makeDem(int nx, int ny, double cell, double west, double south,
                         const std::function<double(double, double)>& f, const std::string& crs = "EPSG:2056") {
  DemRaster d;
  d.grid.nx = nx, d.grid.ny = ny, d.grid.cellSize = cell;
  d.grid.originX = west, d.grid.originY = south + ny * cell;
  d.grid.crsWkt = crs.empty() ? "" : crsToWkt(crs);
  d.height.resize(d.grid.size());
  for (int r = 0; r < ny; ++r)
    for (int c = 0; c < nx; ++c) d.height[d.grid.index(c, r)] = float(f(d.grid.cellCentreX(c), d.grid.cellCentreY(r)));
  d.sourcePath = "test";
  return d;
}

/// Writes a raster with an arbitrary geotransform (for the invalid-raster tests).
inline void writeRawRaster(const std::string& path, int nx, int ny, const double gt[6], const std::vector<float>& values,
                           double nodata = -9999) {
  GDALAllRegister();
  GDALDriver* drv = GetGDALDriverManager()->GetDriverByName("GTiff");
  GDALDataset* ds = drv->Create(path.c_str(), nx, ny, 1, GDT_Float32, nullptr);
  ds->SetGeoTransform(const_cast<double*>(gt));
  ds->GetRasterBand(1)->SetNoDataValue(nodata);
  std::vector<float> v(values);
  if (ds->GetRasterBand(1)->RasterIO(GF_Write, 0, 0, nx, ny, v.data(), nx, ny, GDT_Float32, 0, 0) != CE_None) std::abort();
  GDALClose(ds);
}

struct TestPolygon {
  std::vector<std::pair<double, double>> ring; ///< outer ring (closed automatically)
  double thickness = 0;                        ///< written to the "thickness" field (NaN: left null)
};

/// Writes polygons with a "thickness" field: `driver` "ESRI Shapefile" or "GeoJSON".
inline void writePolygons(const std::string& path, const std::vector<TestPolygon>& polys, const std::string& crs,
                          const std::string& driver = "ESRI Shapefile") {
  GDALAllRegister();
  GDALDriver* drv = GetGDALDriverManager()->GetDriverByName(driver.c_str());
  GDALDataset* ds = drv->Create(path.c_str(), 0, 0, 0, GDT_Unknown, nullptr);
  OGRSpatialReference srs;
  if (!crs.empty()) {
    srs.SetFromUserInput(crs.c_str());
    srs.SetAxisMappingStrategy(OAMS_TRADITIONAL_GIS_ORDER);
  }
  OGRLayer* layer = ds->CreateLayer("polygons", crs.empty() ? nullptr : &srs, wkbPolygon, nullptr);
  OGRFieldDefn field("thickness", OFTReal);
  layer->CreateField(&field);
  for (const auto& p : polys) {
    OGRFeature* f = OGRFeature::CreateFeature(layer->GetLayerDefn());
    if (!std::isnan(p.thickness)) f->SetField("thickness", p.thickness);
    OGRLinearRing ring;
    for (const auto& [x, y] : p.ring) ring.addPoint(x, y);
    ring.closeRings();
    OGRPolygon poly;
    poly.addRing(&ring);
    f->SetGeometry(&poly);
    if (layer->CreateFeature(f) != OGRERR_NONE) std::abort();
    OGRFeature::DestroyFeature(f);
  }
  GDALClose(ds);
}

inline std::vector<std::pair<double, double>> rectangleRing(double x0, double y0, double x1, double y1) {
  return {{x0, y0}, {x1, y0}, {x1, y1}, {x0, y1}};
}

} // namespace talus::test
