#include "io/output/peak_files.h"

#include "io/common/ascii_grid_writer.h"
#include "io/common/geotiff_writer.h"
#include "io/common/names.h"

#include <cmath>
#include <filesystem>
#include <stdexcept>

namespace talus {

std::string avaFrameSimName(const PeakFileSettings& s) {
  std::string rel = safeName(s.releaseName);
  if (rel.find('_') != std::string::npos) rel += "_AF"; // AvaFrame's rule: its parser splits at "_AF_"
  return rel + "_" + s.simHash + "_C_L_" + s.simType + "_mpm";
}

const std::vector<std::string>& peakResultTypes() {
  static const std::vector<std::string> t{"pft", "pfv", "ppr", "pfd"};
  return t;
}

RasterGrid com1dfaGrid(const RasterGrid& dem, double mesh) {
  RasterGrid g = dem;
  // Tolerance: a DEM spanning a whole number of mesh cells within rounding keeps its last one.
  g.nx = int(std::floor(double(dem.nx - 1) * dem.cellSize / mesh + 1e-9)) + 1;
  g.ny = int(std::floor(double(dem.ny - 1) * dem.cellSize / mesh + 1e-9)) + 1;
  g.cellSize = mesh;
  const double x0 = dem.cellCentreX(0), ySouth = dem.cellCentreY(dem.ny - 1);
  g.originX = x0 - 0.5 * mesh;
  g.originY = ySouth - 0.5 * mesh + double(g.ny) * mesh;
  return g;
}

std::vector<float> resampleCentres(const RasterGrid& from, const std::vector<float>& v, float nodata,
                                   const RasterGrid& onto) {
  std::vector<float> out(onto.size(), NAN);
  auto at = [&](int c, int r) -> float {
    if (c < 0 || r < 0 || c >= from.nx || r >= from.ny) return NAN;
    const float x = v[from.index(c, r)];
    return x == nodata || std::isnan(x) ? NAN : x;
  };
  for (int r = 0; r < onto.ny; ++r)
    for (int c = 0; c < onto.nx; ++c) {
      // A centre on the source's edge centres within rounding counts as on them (com1DFA's mesh
      // starts at the DEM's first centre).
      auto snap = [](double f, int n) { return f < 0 && f > -1e-6 ? 0.0 : f > n - 1 && f < n - 1 + 1e-6 ? double(n - 1) : f; };
      const double fx = snap((onto.cellCentreX(c) - from.originX) / from.cellSize - 0.5, from.nx);
      const double fy = snap((from.originY - onto.cellCentreY(r)) / from.cellSize - 0.5, from.ny);
      const int c0 = std::min(int(std::floor(fx)), from.nx - 2), r0 = std::min(int(std::floor(fy)), from.ny - 2);
      const double tx = fx - c0, ty = fy - r0;
      const float a = at(c0, r0), b = at(c0 + 1, r0), d = at(c0, r0 + 1), e = at(c0 + 1, r0 + 1);
      float& o = out[onto.index(c, r)];
      if (!std::isnan(a) && !std::isnan(b) && !std::isnan(d) && !std::isnan(e))
        o = float((1 - ty) * ((1 - tx) * a + tx * b) + ty * ((1 - tx) * d + tx * e));
      else
        o = at(int(std::lround(fx)), int(std::lround(fy)));
    }
  return out;
}

std::vector<std::string> writePeakFiles(const std::string& outDir, const PeakFileSettings& s, const std::string& format,
                                        const RasterGrid& grid, const std::vector<std::vector<float>>& values,
                                        float nodata) {
  namespace fs = std::filesystem;
  if (values.size() != peakResultTypes().size()) throw std::logic_error("writePeakFiles: one raster per result type");
  static const char* units[] = {"m", "m/s", "kPa", "m"};
  static const char* bands[] = {"peak_flow_thickness_slope_normal_m", "peak_flow_velocity_m_s", "peak_pressure_kPa",
                                "peak_flow_depth_vertical_m"};
  fs::create_directories(fs::path(outDir) / "peakFiles");
  std::vector<std::string> files;
  for (size_t i = 0; i < values.size(); ++i) {
    const std::string rel = "peakFiles/" + avaFrameSimName(s) + "_" + peakResultTypes()[i];
    if (format == "asc" || format == "both") {
      writeAsciiGrid((fs::path(outDir) / (rel + ".asc")).string(), grid, values[i], nodata);
      files.push_back(rel + ".asc");
    }
    if (format == "tif" || format == "both") {
      GeoTiffBand b;
      b.description = bands[i];
      b.unit = units[i];
      b.nodata = nodata;
      writeGeoTiff((fs::path(outDir) / (rel + ".tif")).string(), grid, values[i], b);
      files.push_back(rel + ".tif");
    }
  }
  return files;
}

} // namespace talus
