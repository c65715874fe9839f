#include "io/common/geotiff_writer.h"

#include "io/common/atomic_file.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal_priv.h>
#include <mutex>
#include <stdexcept>

namespace talus {

namespace {
void initGdal() {
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
}

std::string gdalError(const std::string& what) {
  const char* msg = CPLGetLastErrorMsg();
  return what + (msg && *msg ? std::string(": ") + msg : std::string());
}
} // namespace

void writeGeoTiff(const std::string& path, const RasterGrid& grid, const std::vector<float>& values,
                  const GeoTiffBand& band) {
  initGdal();
  if (values.size() != grid.size()) throw std::runtime_error("writeGeoTiff: raster size mismatch for " + path);
  GDALDriver* driver = GetGDALDriverManager()->GetDriverByName("GTiff");
  if (!driver) throw std::runtime_error("GDAL has no GTiff driver");
  writeAtomically(path, [&](const std::string& tmp) {
    CPLStringList options;
    options.AddNameValue("COMPRESS", "DEFLATE");
    options.AddNameValue("PREDICTOR", "3"); // floating-point predictor: smaller files for smooth fields
    if (grid.nx >= 256 && grid.ny >= 256) options.AddNameValue("TILED", "YES");
    GDALDataset* ds = driver->Create(tmp.c_str(), grid.nx, grid.ny, 1, GDT_Float32, options.List());
    if (!ds) throw std::runtime_error(gdalError("cannot create " + tmp));
    double gt[6] = {grid.originX, grid.cellSize, 0, grid.originY, 0, -grid.cellSize};
    ds->SetGeoTransform(gt);
    if (!grid.crsWkt.empty()) ds->SetProjection(grid.crsWkt.c_str());
    for (const auto& [k, v] : band.metadata) ds->SetMetadataItem(k.c_str(), v.c_str());
    GDALRasterBand* b = ds->GetRasterBand(1);
    b->SetNoDataValue(band.nodata);
    b->SetDescription(band.description.c_str());
    b->SetUnitType(band.unit.c_str());
    const CPLErr err = b->RasterIO(GF_Write, 0, 0, grid.nx, grid.ny, const_cast<float*>(values.data()), grid.nx,
                                   grid.ny, GDT_Float32, 0, 0);
    if (err != CE_None) {
      GDALClose(ds);
      throw std::runtime_error(gdalError("cannot write " + tmp));
    }
    CPLErrorReset();
    GDALClose(ds); // returns void in GDAL 3.6: a failed flush shows up as the last error
    if (CPLGetLastErrorType() >= CE_Failure) throw std::runtime_error(gdalError("cannot close " + tmp));
  });
}

} // namespace talus
