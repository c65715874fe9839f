#include "io/common/raster_reader.h"

#include "io/common/input_error.h"

#include <gdal_priv.h>

namespace talus {

FloatRaster readFloatRaster(const std::string& path, const std::string& what) {
  GDALAllRegister();
  GDALDataset* ds = static_cast<GDALDataset*>(GDALOpen(path.c_str(), GA_ReadOnly));
  if (!ds) throw InputError(path, "cannot read " + what + " (GDAL cannot open it)");
  FloatRaster f;
  double gt[6];
  ds->GetGeoTransform(gt);
  f.grid.nx = ds->GetRasterXSize(), f.grid.ny = ds->GetRasterYSize();
  f.grid.originX = gt[0], f.grid.originY = gt[3], f.grid.cellSize = gt[1];
  f.values.resize(f.grid.size());
  const CPLErr e = ds->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, f.grid.nx, f.grid.ny, f.values.data(), f.grid.nx,
                                                   f.grid.ny, GDT_Float32, 0, 0);
  if (const char* t = ds->GetMetadataItem("TALUS_TIME_S")) f.timeSeconds = t;
  GDALClose(ds);
  if (e != CE_None) throw InputError(path, "cannot read the values of " + what);
  return f;
}

} // namespace talus
