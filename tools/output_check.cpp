#include "tools/output_check.h"

#include "io/common/h5_file.h"
#include "io/run/checkpoint.h"

#include <algorithm>
#include <cairo.h>
#include <filesystem>
#include <fstream>
#include <gdal_priv.h>
#include <openvdb/openvdb.h>
#include <sstream>

namespace talus {

namespace {

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

bool endsWith(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

/// "" when the file is whole, else what is wrong with it.
std::string problem(const std::filesystem::path& file) {
  const std::string path = file.string(), name = file.filename().string();
  if (endsWith(name, ".tmp") || name.find(".tmp.") != std::string::npos) return "a temporary file left behind";
  if (name == "checkpoint.h5") {
    try {
      inspectCheckpoint(path);
      return "";
    } catch (const std::exception& e) {
      return e.what();
    }
  }
  if (endsWith(name, ".h5")) {
    try {
      h5::Handle f = h5::openFile(path);
      size_t rows = 0, cols = 0;
      h5::readDataset<double>(f, "/particles/position", rows, cols);
      h5::readDataset<float>(f, "/particles/velocity", rows, cols);
      return "";
    } catch (const std::exception& e) {
      return e.what();
    }
  }
  if (endsWith(name, ".vdb")) {
    try {
      openvdb::initialize();
      openvdb::io::File f(path);
      f.open(false);
      const auto grids = f.getGrids();
      f.close();
      return grids && !grids->empty() ? "" : "no grids";
    } catch (const std::exception& e) {
      return e.what();
    }
  }
  if (endsWith(name, ".tif")) {
    GDALAllRegister();
    CPLPushErrorHandler(CPLQuietErrorHandler);
    GDALDataset* ds = GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY);
    std::string why;
    if (!ds) {
      why = std::string("GDAL cannot open it: ") + CPLGetLastErrorMsg();
    } else {
      std::vector<float> v(size_t(ds->GetRasterXSize()) * size_t(ds->GetRasterYSize()));
      if (ds->GetRasterBand(1)->RasterIO(GF_Read, 0, 0, ds->GetRasterXSize(), ds->GetRasterYSize(), v.data(),
                                         ds->GetRasterXSize(), ds->GetRasterYSize(), GDT_Float32, 0, 0) != CE_None)
        why = std::string("GDAL cannot read it: ") + CPLGetLastErrorMsg();
      GDALClose(ds);
    }
    CPLPopErrorHandler();
    return why;
  }
  if (endsWith(name, ".png")) {
    cairo_surface_t* s = cairo_image_surface_create_from_png(path.c_str());
    const cairo_status_t st = cairo_surface_status(s);
    cairo_surface_destroy(s);
    return st == CAIRO_STATUS_SUCCESS ? "" : cairo_status_to_string(st);
  }
  const std::string text = slurp(path);
  if (endsWith(name, ".csv")) {
    if (!endsWith(text, "\n")) return "does not end with a line break";
    std::istringstream in(text);
    std::string line;
    std::getline(in, line);
    const auto columns = std::count(line.begin(), line.end(), ',');
    for (int row = 2; std::getline(in, line); ++row)
      if (std::count(line.begin(), line.end(), ',') != columns) return "row " + std::to_string(row) + " is cut short";
    return "";
  }
  if (endsWith(name, ".json")) return endsWith(text, "}\n") ? "" : "does not end with its closing brace";
  if (endsWith(name, ".ply")) {
    const auto end = text.find("end_header\n"), count = text.find("element vertex ");
    if (end == std::string::npos || count == std::string::npos) return "no PLY header";
    const size_t n = std::stoull(text.substr(count + 15));
    const size_t vertexBytes = 3 * 8 + 4 * 4 + 4 + 3;
    return text.size() == end + 11 + n * vertexBytes ? "" : "holds fewer bytes than its vertices need";
  }
  return "";
}

} // namespace

std::vector<std::string> incompleteOutputFiles(const std::string& dir) {
  std::vector<std::string> out;
  if (!std::filesystem::is_directory(dir)) return {dir + ": no such folder"};
  for (const auto& e : std::filesystem::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file() && !e.is_symlink()) continue;
    const std::string why = problem(e.path());
    if (!why.empty()) out.push_back(std::filesystem::relative(e.path(), dir).string() + ": " + why);
  }
  std::sort(out.begin(), out.end());
  return out;
}

} // namespace talus
