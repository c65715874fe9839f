// libFuzzer target for the DEM reader: any bytes as a raster file (GDAL identifies GeoTIFF, ESRI
// ASCII grids and the rest by content), read with no-data refused or filled, then smoothed.
// Expected: a DemRaster or talus::InputError.
#include "fuzz_support.h"
#include "io/terrain/dem_raster.h"

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  talus::fuzz::smallLimits();
  return 0;
}

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  // The first byte picks the options, the rest is the file.
  talus::DemReadOptions opt;
  opt.fillNodata = data[0] & 1;
  opt.keepNodata = data[0] & 2;
  const std::string path = talus::fuzz::writeInput("dem.tif", data + 1, size - 1);
  try {
    talus::DemRaster dem = talus::readDem(path, opt);
    if (data[0] & 4) talus::smoothDem(dem, 2 * dem.grid.cellSize);
    if (!opt.keepNodata) {
      const talus::HeightField h(dem);
      h.height(dem.grid.originX + dem.grid.cellSize, dem.grid.originY - dem.grid.cellSize);
    }
  } catch (const talus::InputError&) {
  } catch (const std::exception& e) {
    talus::fuzz::fail("raster fuzzer", e.what());
  }
  return 0;
}
