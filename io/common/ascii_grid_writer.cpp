#include "io/common/ascii_grid_writer.h"

#include <cpl_conv.h>
#include <cpl_error.h>
#include <cpl_string.h>
#include <filesystem>
#include <gdal_priv.h>
#include <mutex>
#include <stdexcept>

namespace talus {

void writeAsciiGrid(const std::string& path, const RasterGrid& grid, const std::vector<float>& values, double nodata) {
  namespace fs = std::filesystem;
  static std::once_flag once;
  std::call_once(once, [] { GDALAllRegister(); });
  if (values.size() != grid.size()) throw std::runtime_error("writeAsciiGrid: raster size mismatch for " + path);
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  GDALDriver* aai = GetGDALDriverManager()->GetDriverByName("AAIGrid");
  if (!mem || !aai) throw std::runtime_error("GDAL has no MEM or AAIGrid driver");
  auto fail = [&](const std::string& what) {
    const char* msg = CPLGetLastErrorMsg();
    return std::runtime_error(what + (msg && *msg ? std::string(": ") + msg : std::string()));
  };
  GDALDataset* src = mem->Create("", grid.nx, grid.ny, 1, GDT_Float32, nullptr);
  if (!src) throw fail("cannot create an in-memory raster for " + path);
  double gt[6] = {grid.originX, grid.cellSize, 0, grid.originY, 0, -grid.cellSize};
  src->SetGeoTransform(gt);
  if (!grid.crsWkt.empty()) src->SetProjection(grid.crsWkt.c_str());
  GDALRasterBand* b = src->GetRasterBand(1);
  b->SetNoDataValue(nodata);
  if (b->RasterIO(GF_Write, 0, 0, grid.nx, grid.ny, const_cast<float*>(values.data()), grid.nx, grid.ny, GDT_Float32, 0,
                  0) != CE_None) {
    GDALClose(src);
    throw fail("cannot fill the in-memory raster for " + path);
  }
  // The driver names the .prj after the file: temporary names share the stem, then both move.
  const fs::path p(path), tmp = p.parent_path() / (p.stem().string() + ".tmp" + p.extension().string());
  const fs::path tmpPrj = fs::path(tmp).replace_extension(".prj"), prj = fs::path(path).replace_extension(".prj");
  CPLStringList options;
  options.AddNameValue("SIGNIFICANT_DIGITS", "9");
  CPLSetThreadLocalConfigOption("GDAL_PAM_ENABLED", "NO"); // no .aux.xml beside the grid
  CPLErrorReset();
  GDALDataset* out = aai->CreateCopy(tmp.c_str(), src, FALSE, options.List(), nullptr, nullptr);
  GDALClose(src);
  const bool ok = out != nullptr;
  if (out) GDALClose(out);
  CPLSetThreadLocalConfigOption("GDAL_PAM_ENABLED", nullptr);
  if (!ok || CPLGetLastErrorType() >= CE_Failure) {
    std::error_code ec;
    fs::remove(tmp, ec), fs::remove(tmpPrj, ec);
    throw fail("cannot write " + path);
  }
  if (fs::exists(tmpPrj)) fs::rename(tmpPrj, prj);
  fs::rename(tmp, path);
}

} // namespace talus
