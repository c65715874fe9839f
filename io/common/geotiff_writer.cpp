#include "io/common/geotiff_writer.h"

#include "io/common/atomic_file.h"

#include <atomic>
#include <cpl_conv.h>
#include <cpl_vsi.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <gdal_priv.h>
#include <memory>
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
  // Encoded in GDAL's memory file system, then written with checked writes: GDAL's own messages
  // for a full disk name neither the file nor the cause.
  static std::atomic<unsigned> counter{0};
  const std::string mem = "/vsimem/talus_geotiff_" + std::to_string(counter++) + ".tif";
  CPLStringList options;
  options.AddNameValue("COMPRESS", "DEFLATE");
  options.AddNameValue("PREDICTOR", "3"); // floating-point predictor: smaller files for smooth fields
  if (grid.nx >= 256 && grid.ny >= 256) options.AddNameValue("TILED", "YES");
  GDALDataset* ds = driver->Create(mem.c_str(), grid.nx, grid.ny, 1, GDT_Float32, options.List());
  if (!ds) throw WriteError(path, gdalError("GDAL cannot create the GeoTIFF"));
  double gt[6] = {grid.originX, grid.cellSize, 0, grid.originY, 0, -grid.cellSize};
  ds->SetGeoTransform(gt);
  if (!grid.crsWkt.empty()) ds->SetProjection(grid.crsWkt.c_str());
  for (const auto& [k, v] : band.metadata) ds->SetMetadataItem(k.c_str(), v.c_str());
  GDALRasterBand* b = ds->GetRasterBand(1);
  b->SetNoDataValue(band.nodata);
  b->SetDescription(band.description.c_str());
  b->SetUnitType(band.unit.c_str());
  CPLErrorReset();
  const CPLErr err = b->RasterIO(GF_Write, 0, 0, grid.nx, grid.ny, const_cast<float*>(values.data()), grid.nx,
                                 grid.ny, GDT_Float32, 0, 0);
  GDALClose(ds); // returns void in GDAL 3.6: a failed flush shows up as the last error
  vsi_l_offset size = 0;
  GByte* bytes = VSIGetMemFileBuffer(mem.c_str(), &size, TRUE);
  const std::unique_ptr<GByte, decltype(&VSIFree)> owned(bytes, &VSIFree);
  if (err != CE_None || CPLGetLastErrorType() >= CE_Failure || !bytes)
    throw WriteError(path, gdalError("GDAL cannot encode the GeoTIFF"));
  writeAtomically(path, [&](const std::string& tmp) { writeFileBytes(tmp, bytes, size_t(size)); });
}

} // namespace talus
