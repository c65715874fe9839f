#include "io/terrain/dem_raster.h"

#include "io/common/geotiff_writer.h"
#include "io/common/resource_limits.h"

#include <algorithm>
#include <cmath>
#include <cpl_conv.h>
#include <cpl_error.h>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <gdal_alg.h>
#include <gdal_priv.h>
#include <limits>
#include <memory>
#include <ogr_spatialref.h>
#include <tbb/parallel_for.h>

namespace talus {

namespace {

constexpr float kNan = std::numeric_limits<float>::quiet_NaN();

/// Silences GDAL's own stderr messages while alive; we report its last message ourselves.
struct QuietGdal {
  QuietGdal() { CPLPushErrorHandler(CPLQuietErrorHandler); CPLErrorReset(); }
  ~QuietGdal() { CPLPopErrorHandler(); }
};

std::string lastGdalMessage() {
  std::string m = CPLGetLastErrorMsg();
  std::replace(m.begin(), m.end(), '\n', ' ');
  return m;
}

struct DatasetCloser {
  void operator()(GDALDataset* d) const { GDALClose(GDALDataset::ToHandle(d)); }
};
using DatasetPtr = std::unique_ptr<GDALDataset, DatasetCloser>;

/// GDAL reads a damaged token of an ESRI ASCII grid ("nan", "1.2.3", "12a") as 0 without a word:
/// a wrong height. Every value after the header lines must be a finite number.
void checkAsciiGridValues(const std::string& path) {
  std::ifstream in(path);
  std::string line;
  for (int n = 1; std::getline(in, line); ++n) {
    std::istringstream tokens(line);
    std::string t;
    if (!(tokens >> t) || std::isalpha(static_cast<unsigned char>(t[0]))) continue; // header, blank
    do {
      char* end = nullptr;
      const double v = std::strtod(t.c_str(), &end);
      if (*end != '\0' || !std::isfinite(v) || t.find_first_of("xXnNiI") != std::string::npos)
        throw InputError(path, "line " + std::to_string(n) + ": '" + t.substr(0, 20) + "' is not a number");
    } while (tokens >> t);
  }
}

} // namespace

std::string crsToWkt(const std::string& userInput) {
  if (userInput.empty()) return "";
  QuietGdal quiet;
  OGRSpatialReference srs;
  if (srs.SetFromUserInput(userInput.c_str()) != OGRERR_NONE)
    throw InputError("", "unknown CRS '" + userInput + "'");
  char* wkt = nullptr;
  srs.exportToWkt(&wkt);
  std::string s = wkt ? wkt : "";
  CPLFree(wkt);
  return s;
}

bool sameCrs(const std::string& a, const std::string& b) {
  if (a.empty() || b.empty()) return true;
  QuietGdal quiet;
  OGRSpatialReference sa, sb;
  if (sa.importFromWkt(a.c_str()) != OGRERR_NONE || sb.importFromWkt(b.c_str()) != OGRERR_NONE) return a == b;
  const char* opts[] = {"IGNORE_DATA_AXIS_TO_SRS_AXIS_MAPPING=YES", "CRITERION=EQUIVALENT_EXCEPT_AXIS_ORDER_GEOGCRS",
                        nullptr};
  return sa.IsSame(&sb, opts);
}

std::string crsName(const std::string& wkt) {
  if (wkt.empty()) return "unknown CRS";
  QuietGdal quiet;
  OGRSpatialReference s;
  if (s.importFromWkt(wkt.c_str()) != OGRERR_NONE) return "unparsed CRS";
  std::string name = s.GetName() ? s.GetName() : "unnamed CRS";
  const char* auth = s.GetAuthorityName(nullptr);
  const char* code = s.GetAuthorityCode(nullptr);
  if (auth && code) name += std::string(" (") + auth + ":" + code + ")";
  return name;
}

size_t countNodata(const DemRaster& dem) {
  return size_t(std::count_if(dem.height.begin(), dem.height.end(), [](float h) { return std::isnan(h); }));
}

DemRaster readDem(const std::string& path, const DemReadOptions& options, size_t* filledCells) {
  if (filledCells) *filledCells = 0;
  if (!std::filesystem::exists(path)) throw InputError(path, "file not found");
  if (!std::filesystem::is_regular_file(path)) throw InputError(path, "not a regular file");
  GDALAllRegister();
  QuietGdal quiet;
  DatasetPtr ds(GDALDataset::Open(path.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
  if (!ds) {
    const std::string m = lastGdalMessage();
    throw InputError(path, "not a raster GDAL can read" + (m.empty() ? "" : " (" + m + ")"));
  }
  if (ds->GetRasterCount() < 1) throw InputError(path, "the file holds no raster band");
  if (std::string(ds->GetDriverName()) == "AAIGrid") checkAsciiGridValues(path);
  double gt[6];
  if (ds->GetGeoTransform(gt) != CE_None) throw InputError(path, "the raster has no georeferencing (geotransform)");
  if (gt[2] != 0 || gt[4] != 0)
    throw InputError(path, "rotated or sheared rasters are not supported (geotransform terms " +
                   std::to_string(gt[2]) + ", " + std::to_string(gt[4]) + "); warp it north-up first (gdalwarp)");
  const double cx = gt[1], cy = std::fabs(gt[5]);
  if (!(cx > 0) || !(cy > 0) || !std::isfinite(cx) || !std::isfinite(cy))
    throw InputError(path, "cell size must be positive and finite");
  if (std::fabs(cx - cy) > 1e-9 * cx)
    throw InputError(path, "cells are not square (" + std::to_string(cx) + " x " + std::to_string(cy) +
                   " m); resample it first (gdalwarp -tr D D)");
  DemRaster dem;
  dem.sourcePath = path;
  RasterGrid& g = dem.grid;
  g.nx = ds->GetRasterXSize();
  g.ny = ds->GetRasterYSize();
  if (g.nx < 2 || g.ny < 2) throw InputError(path, "the raster must be at least 2 x 2 cells");
  // A damaged header can claim any size: refuse before allocating it.
  if (double(g.nx) * double(g.ny) > resourceLimits().maxRasterCells)
    throw InputError(path, std::to_string(g.nx) + " x " + std::to_string(g.ny) + " cells, more than the limit of " +
                               std::to_string(resourceLimits().maxRasterCells) + "; crop or resample it");
  if (!std::isfinite(gt[0]) || !std::isfinite(gt[3]) || !std::isfinite(cx * g.nx) || !std::isfinite(cy * g.ny))
    throw InputError(path, "the georeferencing is not finite");
  g.cellSize = cx;
  g.originX = gt[0];
  g.originY = gt[5] < 0 ? gt[3] : gt[3] + g.ny * cy; // south-up rasters are flipped below
  if (const OGRSpatialReference* srs = ds->GetSpatialRef()) {
    char* wkt = nullptr;
    srs->exportToWkt(&wkt);
    g.crsWkt = wkt ? wkt : "";
    CPLFree(wkt);
  }
  if (!options.assignCrs.empty()) {
    std::string want;
    try {
      want = crsToWkt(options.assignCrs);
    } catch (const InputError& e) {
      throw InputError(path, e.what());
    }
    if (!g.crsWkt.empty() && !sameCrs(g.crsWkt, want))
      throw InputError(path, "the file's CRS " + crsName(g.crsWkt) + " differs from the CRS given, " + crsName(want));
    if (g.crsWkt.empty()) g.crsWkt = want;
  }
  GDALRasterBand* band = ds->GetRasterBand(1);
  dem.height.resize(g.size());
  if (band->RasterIO(GF_Read, 0, 0, g.nx, g.ny, dem.height.data(), g.nx, g.ny, GDT_Float32, 0, 0) != CE_None)
    throw InputError(path, "cannot read the raster (" + lastGdalMessage() + ")");
  int hasNodata = 0;
  const double nodata = band->GetNoDataValue(&hasNodata);
  const float nd = float(nodata);
  for (float& h : dem.height)
    if ((hasNodata && (h == nd || (std::isnan(nodata) && std::isnan(h)))) || !std::isfinite(h)) h = kNan;
  if (gt[5] > 0)
    for (int r = 0; r < g.ny / 2; ++r)
      std::swap_ranges(dem.height.begin() + long(g.index(0, r)), dem.height.begin() + long(g.index(0, r)) + g.nx,
                       dem.height.begin() + long(g.index(0, g.ny - 1 - r)));
  const size_t holes = countNodata(dem);
  if (holes > 0 && !options.keepNodata) {
    if (!options.fillNodata) {
      size_t first = 0;
      while (!std::isnan(dem.height[first])) ++first;
      const int col = int(first % size_t(g.nx)), row = int(first / size_t(g.nx));
      throw InputError(path, std::to_string(holes) + " no-data cells (first at column " + std::to_string(col) +
                     ", row " + std::to_string(row) + ", x " + std::to_string(g.cellCentreX(col)) + ", y " +
                     std::to_string(g.cellCentreY(row)) +
                     "); fill them (scene: fill_nodata = true, talus terrain: --fill-nodata) or crop the DEM");
    }
    const size_t n = fillNodata(dem);
    if (filledCells) *filledCells = n;
  }
  return dem;
}

size_t fillNodata(DemRaster& dem) {
  const RasterGrid& g = dem.grid;
  const size_t holes = countNodata(dem);
  if (holes == 0) return 0;
  if (holes == g.size()) throw InputError(dem.sourcePath, "every cell is no-data");
  GDALAllRegister();
  QuietGdal quiet;
  GDALDriver* mem = GetGDALDriverManager()->GetDriverByName("MEM");
  DatasetPtr ds(mem->Create("", g.nx, g.ny, 2, GDT_Float32, nullptr));
  if (!ds) throw InputError(dem.sourcePath, "cannot allocate the fill buffer");
  std::vector<float> mask(g.size());
  for (size_t i = 0; i < g.size(); ++i) mask[i] = std::isnan(dem.height[i]) ? 0.f : 1.f;
  std::vector<float> h(dem.height); // holes stay NaN: a cell the search cannot reach stays NaN
  GDALRasterBand* hb = ds->GetRasterBand(1);
  GDALRasterBand* mb = ds->GetRasterBand(2);
  if (hb->RasterIO(GF_Write, 0, 0, g.nx, g.ny, h.data(), g.nx, g.ny, GDT_Float32, 0, 0) != CE_None ||
      mb->RasterIO(GF_Write, 0, 0, g.nx, g.ny, mask.data(), g.nx, g.ny, GDT_Float32, 0, 0) != CE_None)
    throw InputError(dem.sourcePath, "cannot fill no-data (" + lastGdalMessage() + ")");
  // The search costs time in proportion to its radius for every hole (a 4 x 45 000-cell raster
  // of holes took minutes with the raster's length): capped, holes farther from data are refused.
  const double searchCells = double(std::min(std::max(g.nx, g.ny), kMaxFillCells));
  // GDAL's default work files are GeoTIFFs in the current folder, left behind when a run is
  // killed; the DEM is in memory anyway.
  const char* fillOptions[] = {"TEMP_FILE_DRIVER=MEM", nullptr};
  if (GDALFillNodata(GDALRasterBand::ToHandle(hb), GDALRasterBand::ToHandle(mb), searchCells, 0, 2,
                     const_cast<char**>(fillOptions), nullptr, nullptr) != CE_None)
    throw InputError(dem.sourcePath, "filling no-data failed (" + lastGdalMessage() + ")");
  if (hb->RasterIO(GF_Read, 0, 0, g.nx, g.ny, h.data(), g.nx, g.ny, GDT_Float32, 0, 0) != CE_None)
    throw InputError(dem.sourcePath, "cannot fill no-data (" + lastGdalMessage() + ")");
  size_t unreached = 0;
  for (size_t i = 0; i < g.size(); ++i) unreached += std::isnan(h[i]) || !std::isfinite(h[i]);
  if (unreached > 0)
    throw InputError(dem.sourcePath, std::to_string(unreached) + " no-data cells lie more than " +
                                         std::to_string(kMaxFillCells) +
                                         " cells from any valid cell and cannot be filled; crop the DEM");
  for (size_t i = 0; i < g.size(); ++i)
    if (std::isnan(dem.height[i])) dem.height[i] = h[i];
  return holes;
}

void smoothDem(DemRaster& dem, double radius) {
  if (!(radius > 0)) return;
  const RasterGrid& g = dem.grid;
  const double sigma = 0.5 * radius; // radius = the Gaussian's 1/e^2 radius
  const int half = int(std::floor(3 * sigma / g.cellSize));
  if (half < 1) return;
  std::vector<double> w(size_t(2 * half + 1));
  for (int k = -half; k <= half; ++k) w[size_t(k + half)] = std::exp(-0.5 * std::pow(k * g.cellSize / sigma, 2));
  // Normalised convolution: smooth value*valid and valid separately, divide at the end.
  std::vector<double> num(g.size()), den(g.size()), tn(g.size()), td(g.size());
  for (size_t i = 0; i < g.size(); ++i) {
    const bool ok = !std::isnan(dem.height[i]);
    num[i] = ok ? dem.height[i] : 0.0;
    den[i] = ok ? 1.0 : 0.0;
  }
  tbb::parallel_for(0, g.ny, [&](int r) { // along rows
    for (int c = 0; c < g.nx; ++c) {
      double sn = 0, sd = 0;
      for (int k = std::max(-half, -c); k <= std::min(half, g.nx - 1 - c); ++k) {
        const size_t j = g.index(c + k, r);
        sn += w[size_t(k + half)] * num[j];
        sd += w[size_t(k + half)] * den[j];
      }
      tn[g.index(c, r)] = sn, td[g.index(c, r)] = sd;
    }
  });
  tbb::parallel_for(0, g.ny, [&](int r) { // along columns
    for (int c = 0; c < g.nx; ++c) {
      const size_t i = g.index(c, r);
      if (std::isnan(dem.height[i])) continue;
      double sn = 0, sd = 0;
      for (int k = std::max(-half, -r); k <= std::min(half, g.ny - 1 - r); ++k) {
        const size_t j = g.index(c, r + k);
        sn += w[size_t(k + half)] * tn[j];
        sd += w[size_t(k + half)] * td[j];
      }
      dem.height[i] = float(sn / sd);
    }
  });
}

void writeDemGeoTiff(const DemRaster& dem, const std::string& path) {
  GeoTiffBand band;
  band.description = "elevation_m";
  band.unit = "m";
  std::vector<float> h(dem.height);
  for (float& v : h)
    if (std::isnan(v)) v = float(band.nodata);
  writeGeoTiff(path, dem.grid, h, band);
}

// ---------------------------------------------------------------------------------------------

HeightField::HeightField(const DemRaster& dem) : dem_(&dem) {
  const RasterGrid& g = dem.grid;
  gx_.resize(g.size());
  gy_.resize(g.size());
  hmin_ = std::numeric_limits<float>::max(), hmax_ = -hmin_;
  for (float h : dem.height)
    if (!std::isnan(h)) hmin_ = std::min(hmin_, h), hmax_ = std::max(hmax_, h);
  for (int r = 0; r < g.ny; ++r)
    for (int c = 0; c < g.nx; ++c) {
      const int c0 = std::max(c - 1, 0), c1 = std::min(c + 1, g.nx - 1);
      const int r0 = std::max(r - 1, 0), r1 = std::min(r + 1, g.ny - 1);
      gx_[g.index(c, r)] = float((dem.height[g.index(c1, r)] - dem.height[g.index(c0, r)]) / ((c1 - c0) * g.cellSize));
      // Rows run south, so dh/dy = -(h[r+1] - h[r-1]) / (2 cell).
      gy_[g.index(c, r)] = float(-(dem.height[g.index(c, r1)] - dem.height[g.index(c, r0)]) / ((r1 - r0) * g.cellSize));
    }
}

namespace {
/// Cell-centre coordinates (u along columns, v along rows) of world (x, y), clamped to the
/// centres; (i, j) is the patch's lower corner and (fu, fv) the position in it.
struct Patch {
  int i, j;
  double fu, fv;
  bool clampU, clampV;
};
inline Patch locatePatch(const RasterGrid& g, double x, double y) {
  double u = (x - g.originX) / g.cellSize - 0.5, v = (g.originY - y) / g.cellSize - 0.5;
  Patch p;
  p.clampU = u < 0 || u > g.nx - 1;
  p.clampV = v < 0 || v > g.ny - 1;
  u = std::clamp(u, 0.0, double(g.nx - 1));
  v = std::clamp(v, 0.0, double(g.ny - 1));
  p.i = std::min(int(u), g.nx - 2);
  p.j = std::min(int(v), g.ny - 2);
  p.fu = u - p.i, p.fv = v - p.j;
  return p;
}
template <class T> inline double bilinear(const std::vector<T>& a, const RasterGrid& g, const Patch& p) {
  const size_t i00 = g.index(p.i, p.j);
  const double h00 = a[i00], h10 = a[i00 + 1], h01 = a[i00 + size_t(g.nx)], h11 = a[i00 + size_t(g.nx) + 1];
  return (1 - p.fv) * ((1 - p.fu) * h00 + p.fu * h10) + p.fv * ((1 - p.fu) * h01 + p.fu * h11);
}
} // namespace

double sampleBilinear(const RasterGrid& g, const std::vector<float>& values, double x, double y) {
  return bilinear(values, g, locatePatch(g, x, y));
}

double HeightField::height(double x, double y) const {
  return bilinear(dem_->height, dem_->grid, locatePatch(dem_->grid, x, y));
}

double HeightField::heightAndGradient(double x, double y, double& gx, double& gy) const {
  const RasterGrid& g = dem_->grid;
  const Patch p = locatePatch(g, x, y);
  const size_t i00 = g.index(p.i, p.j);
  const std::vector<float>& a = dem_->height;
  const double h00 = a[i00], h10 = a[i00 + 1], h01 = a[i00 + size_t(g.nx)], h11 = a[i00 + size_t(g.nx) + 1];
  const double du = (1 - p.fv) * (h10 - h00) + p.fv * (h11 - h01);
  const double dv = (1 - p.fu) * (h01 - h00) + p.fu * (h11 - h10);
  gx = p.clampU ? 0.0 : du / g.cellSize;
  gy = p.clampV ? 0.0 : -dv / g.cellSize;
  return (1 - p.fv) * ((1 - p.fu) * h00 + p.fu * h10) + p.fv * ((1 - p.fu) * h01 + p.fu * h11);
}

void HeightField::slopeGradient(double x, double y, double& gx, double& gy) const {
  const Patch p = locatePatch(dem_->grid, x, y);
  gx = bilinear(gx_, dem_->grid, p);
  gy = bilinear(gy_, dem_->grid, p);
}

double HeightField::slope(double x, double y) const {
  double gx, gy;
  slopeGradient(x, y, gx, gy);
  return std::atan(std::sqrt(gx * gx + gy * gy));
}

} // namespace talus
