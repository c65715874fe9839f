#include "io/terrain/avaframe_folder.h"

#include "io/common/input_error.h"
#include "io/common/polyline.h"
#include "io/terrain/dem_raster.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cpl_conv.h>
#include <cpl_error.h>
#include <filesystem>
#include <gdal_priv.h>
#include <map>
#include <memory>
#include <ogrsf_frmts.h>
#include <set>

namespace talus {

namespace fs = std::filesystem;

namespace {

struct QuietGdal {
  QuietGdal() { CPLPushErrorHandler(CPLQuietErrorHandler); CPLErrorReset(); }
  ~QuietGdal() { CPLPopErrorHandler(); }
};
struct DatasetCloser {
  void operator()(GDALDataset* d) const { GDALClose(GDALDataset::ToHandle(d)); }
};
using Dataset = std::unique_ptr<GDALDataset, DatasetCloser>;

std::string lower(std::string s) {
  for (char& c : s) c = char(std::tolower(static_cast<unsigned char>(c)));
  return s;
}

std::string list(const std::vector<std::string>& v) {
  std::string s;
  for (const auto& e : v) s += (s.empty() ? "" : ", ") + e;
  return s;
}

/// Files of a folder by lower-case extension, sorted by name (directory order is arbitrary).
std::map<std::string, std::vector<fs::path>> filesByExtension(const fs::path& dir) {
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.is_regular_file()) files.push_back(e.path());
  std::sort(files.begin(), files.end());
  std::map<std::string, std::vector<fs::path>> out;
  for (const auto& f : files) out[lower(f.extension().string())].push_back(f);
  return out;
}

/// The shapefiles of `dir`; a .shp needs its .shx and .dbf, and the other parts of a shapefile
/// (.prj, .dbf, ...) need their .shp: a half-copied shapefile is named, not skipped.
std::vector<fs::path> shapefiles(const fs::path& dir) {
  auto byExt = filesByExtension(dir);
  std::set<std::string> stems;
  for (const auto& f : byExt[".shp"]) stems.insert(f.stem().string());
  for (const char* part : {".shx", ".dbf", ".prj", ".cpg", ".qpj"})
    for (const auto& f : byExt[part])
      if (!stems.count(f.stem().string()))
        throw InputError(f.string(), "no " + f.stem().string() + ".shp beside it (a shapefile is .shp, .shx and .dbf)");
  for (const auto& shp : byExt[".shp"])
    for (const char* part : {".shx", ".dbf"}) {
      bool found = false; // the parts' extensions may differ in case
      for (const auto& f : byExt[part]) found = found || f.stem() == shp.stem();
      if (!found) throw InputError(shp.string(), std::string("incomplete shapefile: no ") + shp.stem().string() + part);
    }
  return byExt[".shp"];
}

Dataset openVector(const fs::path& path) {
  GDALAllRegister();
  QuietGdal quiet;
  Dataset ds(GDALDataset::Open(path.c_str(), GDAL_OF_VECTOR | GDAL_OF_READONLY));
  if (!ds || ds->GetLayerCount() < 1)
    throw InputError(path.string(), "not a shapefile GDAL/OGR can read (" + std::string(CPLGetLastErrorMsg()) + ")");
  return ds;
}

std::string layerCrs(OGRLayer* layer) {
  std::string wkt;
  if (const OGRSpatialReference* srs = layer->GetSpatialRef()) {
    char* s = nullptr;
    srs->exportToWkt(&s);
    wkt = s ? s : "";
    CPLFree(s);
  }
  return wkt;
}

int fieldIndex(OGRFeatureDefn* defn, const std::string& name) {
  for (int i = 0; i < defn->GetFieldCount(); ++i)
    if (lower(defn->GetFieldDefn(i)->GetNameRef()) == name) return i;
  return -1;
}

const char* geometryName(OGRwkbGeometryType t) { return OGRGeometryTypeToName(t); }

/// Polygon features and their AvaFrame attributes. AvaFrame's rule for thickness: every feature
/// has one or none has (then a value comes from the configuration); some but not all is an error.
AvaFrameAreas readAreas(const fs::path& shp) {
  Dataset ds = openVector(shp);
  OGRLayer* layer = ds->GetLayer(0);
  AvaFrameAreas a;
  a.path = shp.string();
  a.name = shp.stem().string();
  a.crsWkt = layerCrs(layer);
  OGRFeatureDefn* defn = layer->GetLayerDefn();
  const int fThick = fieldIndex(defn, "thickness"), fD0 = fieldIndex(defn, "d0"), fCi = fieldIndex(defn, "ci95");
  const int fName = fieldIndex(defn, "name");
  const int fT = fThick >= 0 ? fThick : fD0;
  size_t missing = 0;
  layer->ResetReading();
  for (auto& feat : *layer) {
    const OGRGeometry* g = feat->GetGeometryRef();
    const auto type = g ? wkbFlatten(g->getGeometryType()) : wkbNone;
    if (type != wkbPolygon && type != wkbMultiPolygon)
      throw InputError(a.path, "feature " + std::to_string(feat->GetFID()) + " is " +
                                   (g ? std::string("a ") + geometryName(type) : std::string("empty")) +
                                   ", expected polygons");
    AvaFrameFeature f;
    f.name = fName >= 0 && feat->IsFieldSetAndNotNull(fName) ? feat->GetFieldAsString(fName)
                                                              : "feature " + std::to_string(feat->GetFID());
    f.thickness = fT >= 0 && feat->IsFieldSetAndNotNull(fT) ? feat->GetFieldAsDouble(fT) : NAN;
    f.ci95 = fCi >= 0 && feat->IsFieldSetAndNotNull(fCi) ? feat->GetFieldAsDouble(fCi) : NAN;
    if (std::isnan(f.thickness)) ++missing;
    else if (!(f.thickness >= 0) || !std::isfinite(f.thickness))
      throw InputError(a.path, "feature " + std::to_string(feat->GetFID()) + " has thickness " +
                                   std::to_string(f.thickness) + " (must be a non-negative number of metres)");
    a.features.push_back(f);
  }
  if (a.features.empty()) throw InputError(a.path, "no polygon features");
  if (missing > 0 && missing < a.features.size())
    throw InputError(a.path, "not all features have a thickness value (" + std::to_string(missing) + " of " +
                                 std::to_string(a.features.size()) + " have none): AvaFrame takes all or none");
  if (missing == 0) a.thicknessField = fThick >= 0 ? "thickness" : "d0";
  return a;
}

std::string vectorCrs(const fs::path& path) {
  Dataset ds = openVector(path);
  return layerCrs(ds->GetLayer(0));
}

Eigen::Vector2d readPoint(const fs::path& shp, std::string& crs) {
  Dataset ds = openVector(shp);
  OGRLayer* layer = ds->GetLayer(0);
  crs = layerCrs(layer);
  layer->ResetReading();
  for (auto& feat : *layer) {
    const OGRGeometry* g = feat->GetGeometryRef();
    if (g && wkbFlatten(g->getGeometryType()) == wkbPoint) return {g->toPoint()->getX(), g->toPoint()->getY()};
    throw InputError(shp.string(), "expected a point feature");
  }
  throw InputError(shp.string(), "no point feature");
}

/// The single shapefile of ENT/, RES/ or SECREL/ (AvaFrame takes one), or none.
std::optional<fs::path> single(const fs::path& dir) {
  if (!fs::is_directory(dir)) return std::nullopt;
  const auto shps = shapefiles(dir);
  if (shps.empty()) return std::nullopt;
  if (shps.size() > 1) {
    std::vector<std::string> names;
    for (const auto& s : shps) names.push_back(s.filename().string());
    throw InputError(dir.string(), "AvaFrame takes one shapefile here; found " + list(names));
  }
  return shps.front();
}

} // namespace

const AvaFrameAreas& AvaFrameFolder::release(const std::string& want) const {
  std::vector<std::string> names;
  for (const auto& r : releases) {
    if (r.name == want || (want.empty() && releases.size() == 1)) return r;
    names.push_back(r.name);
  }
  throw InputError(dir + "/Inputs/REL", (want.empty() ? std::string("several release scenarios (") + list(names) +
                                                            "): choose one with avaframe.release_scenario"
                                                      : "no release scenario '" + want + "' (scenarios: " + list(names) + ")"));
}

AvaFrameFolder readAvaFrameFolder(const std::string& dirIn) {
  fs::path dir = fs::path(dirIn).lexically_normal();
  if (dir.filename().empty()) dir = dir.parent_path(); // "avaWog/" -> "avaWog"
  if (!fs::is_directory(dir)) throw InputError(dirIn, "AvaFrame folder not found");
  if (dir.filename() == "Inputs" && !fs::is_directory(dir / "Inputs")) dir = dir.parent_path(); // given Inputs/ itself
  const fs::path in = dir / "Inputs";
  if (!fs::is_directory(in)) throw InputError(dir.string(), "not an AvaFrame avalanche folder (no Inputs/ inside)");

  AvaFrameFolder f;
  f.dir = dir.string();
  f.name = dir.filename().string();
  auto top = filesByExtension(in);
  std::vector<fs::path> dems = top[".asc"];
  for (const char* e : {".tif", ".tiff"}) dems.insert(dems.end(), top[e].begin(), top[e].end());
  if (dems.empty()) throw InputError(in.string(), "no DEM (AvaFrame expects one *.asc or *.tif here)");
  if (dems.size() > 1) {
    std::vector<std::string> names;
    for (const auto& d : dems) names.push_back(d.filename().string());
    throw InputError(in.string(), "more than one DEM (" + list(names) + "); AvaFrame takes one");
  }
  f.dem = dems.front().string();
  {
    GDALAllRegister();
    QuietGdal quiet;
    Dataset ds(GDALDataset::Open(f.dem.c_str(), GDAL_OF_RASTER | GDAL_OF_READONLY));
    if (!ds) throw InputError(f.dem, "not a raster GDAL can read (" + std::string(CPLGetLastErrorMsg()) + ")");
    f.demCrsWkt = ds->GetProjectionRef() ? ds->GetProjectionRef() : "";
  }
  if (!top[".ini"].empty()) f.notes.push_back(in.string() + "/*.ini: AvaFrame configuration, not read (the scene file sets materials, dx and end time)");

  const fs::path rel = in / "REL";
  if (!fs::is_directory(rel)) throw InputError(in.string(), "no REL/ folder (release areas)");
  {
    auto byExt = filesByExtension(rel);
    for (const char* e : {".asc", ".tif", ".tiff"})
      if (!byExt[e].empty())
        throw InputError(byExt[e].front().string(), "release rasters are not supported yet: give release polygons (shapefiles)");
    if (!byExt[".csv"].empty())
      f.notes.push_back(byExt[".csv"].front().string() + ": time-dependent release, not applied (everything is released at t = 0)");
  }
  for (const auto& shp : shapefiles(rel)) f.releases.push_back(readAreas(shp));
  if (f.releases.empty()) throw InputError(rel.string(), "no release shapefile (*.shp)");
  if (auto e = single(in / "ENT")) f.entrainment = readAreas(*e);
  if (auto r = single(in / "RES")) {
    f.resistance = readAreas(*r);
    f.notes.push_back(f.resistance->path + ": " + std::to_string(f.resistance->features.size()) +
                      " resistance area(s) read");
  }
  if (auto s = single(in / "SECREL")) {
    f.secondaryRelease = readAreas(*s);
  }
  if (auto d = single(in / "DAM")) f.damFile = d->string();
  if (fs::is_directory(in / "RASTERS") && !fs::is_empty(in / "RASTERS"))
    f.notes.push_back((in / "RASTERS").string() + ": friction rasters (spatialVoellmy), not applied");

  // Every input in one CRS (AvaFrame's rule); a DEM without one (.asc without .prj) takes theirs.
  std::vector<std::pair<std::string, std::string>> crs; // (file, wkt)
  auto addCrs = [&](const std::string& file, const std::string& wkt) {
    if (!wkt.empty()) crs.emplace_back(file, wkt);
  };
  for (const auto& r : f.releases) addCrs(r.path, r.crsWkt);
  for (const auto* o : {&f.entrainment, &f.resistance, &f.secondaryRelease})
    if (*o) addCrs((*o)->path, (*o)->crsWkt);

  const fs::path line = in / "LINES" / "path_aimec.shp";
  if (fs::is_directory(in / "LINES")) shapefiles(in / "LINES"); // a half-copied line file is named
  if (fs::exists(line)) {
    f.thalweg = Polyline::parse(line.string()).points(); // its first line feature
    f.thalwegFile = line.string();
    addCrs(f.thalwegFile, vectorCrs(line));
  }
  const fs::path split = in / "POINTS" / "splitPoint.shp";
  if (fs::is_directory(in / "POINTS")) shapefiles(in / "POINTS");
  if (fs::exists(split)) {
    std::string c;
    f.splitPoint = readPoint(split, c);
    addCrs(split.string(), c);
  }
  const std::string reference = !f.demCrsWkt.empty() ? f.demCrsWkt : crs.empty() ? "" : crs.front().second;
  const std::string referenceFile = !f.demCrsWkt.empty() ? f.dem : crs.empty() ? "" : crs.front().first;
  for (const auto& [file, wkt] : crs)
    if (!sameCrs(wkt, reference))
      throw InputError(file, "its CRS, " + crsName(wkt) + ", differs from " + referenceFile + "'s, " + crsName(reference) +
                                 " (AvaFrame needs one projection for all inputs)");
  return f;
}

std::vector<ResistanceRegion> resistanceRegions(const AvaFrameFolder& folder) {
  std::vector<ResistanceRegion> out;
  if (!folder.resistance) return out;
  for (size_t i = 0; i < folder.resistance->features.size(); ++i) {
    ResistanceRegion r; // AvaFrame attaches no per-area attributes: its configuration's defaults
    r.polygonFile = folder.resistance->path;
    r.feature = int(i);
    out.push_back(r);
  }
  return out;
}

} // namespace talus
