#include "io/output/peak_files.h"

#include "io/common/ascii_grid_writer.h"
#include "io/common/geotiff_writer.h"
#include "io/common/names.h"

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
