// libFuzzer target for the polygon reader (release areas, covers, reservoirs): any bytes as a
// GeoJSON file, or as the three files of a shapefile (.shp, .shx, .dbf), read with and without
// a thickness attribute, then queried. Expected: a PolygonSet or talus::InputError.
#include "fuzz_support.h"
#include "io/terrain/polygon_set.h"

#include <cstring>

extern "C" int LLVMFuzzerInitialize(int*, char***) {
  talus::fuzz::smallLimits();
  return 0;
}

namespace {
/// A shapefile input: [u32 .shp length][u32 .shx length][.shp][.shx][.dbf].
std::string writeShapefile(const uint8_t* data, size_t size) {
  uint32_t n[2] = {0, 0};
  if (size >= 8) std::memcpy(n, data, 8);
  size_t at = size >= 8 ? 8 : size;
  const char* ext[3] = {"shp", "shx", "dbf"};
  for (int i = 0; i < 3; ++i) {
    const size_t len = i < 2 ? std::min<size_t>(n[i], size - at) : size - at;
    talus::fuzz::writeInput(std::string("area.") + ext[i], data + at, len);
    at += len;
  }
  return talus::fuzz::workDir() + "/area.shp";
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t* data, size_t size) {
  if (size < 1) return 0;
  const std::string path =
      data[0] & 1 ? writeShapefile(data + 1, size - 1) : talus::fuzz::writeInput("area.geojson", data + 1, size - 1);
  try {
    const talus::PolygonSet p = talus::PolygonSet::read(path, data[0] & 2 ? "thickness" : "");
    double x0, y0, x1, y1;
    p.bounds(x0, y0, x1, y1);
    for (int i = 0; i <= 4; ++i) p.locate(x0 + (x1 - x0) * i / 4, y0 + (y1 - y0) * (4 - i) / 4);
  } catch (const talus::InputError&) {
  } catch (const std::exception& e) {
    talus::fuzz::fail("polygon fuzzer", e.what());
  }
  return 0;
}
